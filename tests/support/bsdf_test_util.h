// Shared test harness for BSDFs (used by every material test).
//
// What it checks, given a BSDF and an outgoing direction wo (local frame):
//  (a) chi2Test: goodness of fit of sample() against pdf() — the method of Mitsuba's chi2 test
//      (W. Jakob): the sphere is cut into a (θ, φ) grid; the expected count of each cell is
//      N · ∫cell pdf dω (composite Simpson rule in θ and φ, sinθ Jacobian); observed counts come
//      from N calls of sample() with a fixed seed. Samples that fail (nullopt or pdf = 0) and the
//      probability mass the pdf leaves outside the sphere (1 − ∫pdf, e.g. Phong lobes clipped by
//      the horizon) form one extra "failed" cell. Cells with expected count < 5 are pooled
//      (sorted by expected count, smallest first, until the pool reaches 5). Pearson's χ² with
//      dof = cells − 1 gives a p-value Q(dof/2, χ²/2) (regularised upper incomplete gamma);
//      the null hypothesis is rejected at significance α with the Šidák correction for the
//      number of tests: α' = 1 − (1 − α)^(1/numTests). An observed sample in a cell whose
//      expected count is 0 fails immediately. Specular (delta) samples are not allowed here.
//  (b) checkConsistency: for non-specular samples, sample().f == eval(wo, wi) and
//      sample().pdf == pdf(wo, wi) (relative tolerance), f finite and non-negative.
//  (c) pdfIntegral: ∫ pdf(wo, wi) dωi by uniform sphere sampling, with its standard error;
//      tests assert integral ≤ 1 + k·σ.
//  (d) albedo (white furnace): directional albedo ∫ f |cosθi| dωi per channel, estimated with
//      sample() weights (includes specular lobes) with standard errors; tests assert ≤ 1 + k·σ.
//  (e) reciprocityError: max relative difference of eval(wo, wi) and eval(wi, wo) over random
//      pairs in the upper hemisphere (for reflection lobes).
// Everything is deterministic (fixed seeds).
#pragma once

#include <functional>
#include <initializer_list>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "materials/albedo.h"
#include "core/arena.h"
#include "core/properties.h"
#include "materials/bsdf.h"
#include "materials/material.h"
#include "spectral/wavelengths.h"

namespace iris::test {

/// Direction in the xz-plane with the given cosθ (φ = 0), or at azimuth phi.
vec3 dirFromCos(float cosTheta, float phi = 0.0f);

/// A material created through the registry from Properties, and a BSDF from it.
struct BSDFInstance {
    std::shared_ptr<Material> material;
    std::unique_ptr<Arena> arena;
    SampledWavelengths wl;
    const BSDF* bsdf = nullptr;
};

using Param = std::pair<std::string, PropertyValue>;
/// Properties for a plugin of `type` (tag "bsdf") with the given parameters.
std::shared_ptr<Properties> makeProps(const std::string& type, std::initializer_list<Param> params);
/// Create the material through MaterialRegistry (unknown parameters throw) and a BSDF for wl.
BSDFInstance makeBSDF(const Properties& props, SampledWavelengths wl);
BSDFInstance makeBSDF(const std::string& type, std::initializer_list<Param> params,
                      SampledWavelengths wl = SampledWavelengths::rgb(defaultChannelWavelengths()));
/// Mark `p` as an object of a scene file of format version `formatVersion` (0: Mitsuba 0.6, 2/3:
/// Mitsuba 3; Properties::formatVersion) and upgrade it as the loader does
/// (render/loader/scene_upgrade.h): what a plugin reads from such a file.
void asSceneVersion(const PropertiesPtr& p, int formatVersion);
/// makeBSDF for an object of a scene file of format version `formatVersion` (asSceneVersion), for
/// plugins whose semantics depend on it.
BSDFInstance makeBSDFVersion(int formatVersion, const std::string& type, std::initializer_list<Param> params,
                             SampledWavelengths wl = SampledWavelengths::rgb(defaultChannelWavelengths()));

struct Chi2Options {
    int thetaBins = 20;       // over [0, π]; keep even so the horizon is a cell boundary
    int phiBins = 40;         // over [0, 2π)
    int samples = 500000;
    int simpsonPoints = 8;    // initial points per cell and dimension (even); refined adaptively
    uint64_t seed = 1;
    double significance = 0.01;
    int numTests = 1;         // for the Šidák correction
    TransportMode mode = TransportMode::Radiance;
};

struct Chi2Result {
    bool passed = false;
    double chi2 = 0, pValue = 0, threshold = 0;
    int dof = 0;
    double failedFraction = 0;  // observed fraction of failed samples
    double pdfMass = 0;         // ∫ pdf over the sphere (Simpson)
    std::string message;
};

Chi2Result chi2Test(const BSDF& bsdf, const vec3& wo, const Chi2Options& opt = {});

struct ConsistencyResult {
    int samples = 0, nonSpecular = 0, specular = 0;
    float maxRelErrF = 0, maxRelErrPdf = 0;
    int invalid = 0;  // NaN/inf/negative values
    std::string message;  // first problem found
};
ConsistencyResult checkConsistency(const BSDF& bsdf, const vec3& wo, int samples = 20000, uint64_t seed = 2,
                                   TransportMode mode = TransportMode::Radiance);

using Estimate = AlbedoEstimate;  // a Monte Carlo mean and its standard error (materials/albedo.h)
Estimate pdfIntegral(const BSDF& bsdf, const vec3& wo, int samples = 400000, uint64_t seed = 3,
                     TransportMode mode = TransportMode::Radiance);

/// Directional albedo per channel (size = number of wavelengths of the BSDF's spectra).
std::vector<Estimate> albedo(const BSDF& bsdf, const vec3& wo, int samples = 400000, uint64_t seed = 4,
                             TransportMode mode = TransportMode::Radiance);
/// Albedo split into reflection (wi.z > 0) and transmission (wi.z < 0) parts, channel `c`.
std::pair<Estimate, Estimate> albedoSplit(const BSDF& bsdf, const vec3& wo, int c, int samples = 400000,
                                          uint64_t seed = 5, TransportMode mode = TransportMode::Radiance);

/// Max over random (wo, wi) pairs in the upper hemisphere of |f(wo,wi) − f(wi,wo)| / max(f, floor).
float reciprocityError(const BSDF& bsdf, int pairs = 2000, uint64_t seed = 6, float floor = 1e-3f);

/// Regularised upper incomplete gamma Q(a, x) (series / continued fraction, Press et al.,
/// Numerical Recipes 3rd ed. §6.2). Exposed for its own test.
double gammaQ(double a, double x);

}  // namespace iris::test
