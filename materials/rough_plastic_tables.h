// Precomputed transmittances of a rough dielectric interface, for the rough plastic model
// (Jakob's "roughplastic"; thesis 000 §2.5, eqs. 2.37–2.54) and the thesis' proposed model (§3.2).
//
//   T(η, α, μ)  = ∫ f_t(ωi, ωt) |cosθt| dωt                          (eqs. 2.37/2.40 with the
//                 directional transmittance of a microfacet dielectric    cosine of the measure)
//                 (Walter et al. 2007 BTDF, Smith G = G1 G1, exact Λ) lit from the outside at
//                 cosθi = μ with relative index η = η_int/η_ext ≥ 1.
//   Td(η, α)    = (1/η²) · 2 ∫₀¹ T(η, α, μ) μ dμ                       (eqs. 2.39/2.43)
//                 the transmittance of the coat for uniform (Lambertian) light from INSIDE,
//                 obtained from the outside values by reciprocity (f_t/η_t² is symmetric).
//                 The coat's internal diffuse reflectance is Fdr = 1 − Td.
//
// Tables are computed by deterministic quadrature (Gauss-Legendre, split at the kinks of the
// integrand) in parallel (TBB), only when a material asks for them (roughPlasticTables(type)),
// once per distribution, and cached on disk (IRIS_CACHE_DIR, else $XDG_CACHE_HOME/iris, else
// ~/.cache/iris). They are read with Catmull-Rom cubic interpolation (eqs. 2.44–2.51).
// See docs/thesis_models.md for the resolution and the measured interpolation error.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "materials/microfacet.h"

namespace iris {

struct RoughTableResolution {
    int nEta = 24, nAlpha = 32, nMu = 48;  // grid sizes (see docs/thesis_models.md)
    int quadrature = 16;                   // Gauss-Legendre points per dimension and piece
};

class RoughTransmittanceTables {
public:
    // Domain: η ∈ [1, 3] with nodes η_i = 1 + 2 (i/(nη−1))² (T varies like sqrt(η − 1) near
    // η = 1); α ∈ [0, 1] with nodes α_k = (k/(nα−1))²; μ ∈ [0, 1] uniform.
    static constexpr float kEtaMin = 1.0f, kEtaMax = 3.0f, kAlphaMax = 1.0f;

    MicrofacetType type = MicrofacetType::Beckmann;
    RoughTableResolution res;
    std::vector<float> ext;      // T(η, α, μ), index (iEta · nAlpha + iAlpha) · nMu + iMu
    std::vector<float> diffuse;  // Td(η, α), index iEta · nAlpha + iAlpha

    /// The (η, α) part of the tricubic stencil, collapsed: up to 16 μ-lines of the table with their
    /// weights. Lets a BSDF with fixed η, α look up T at several μ without recomputing it.
    struct Line {
        int offset[16];
        float weight[16];
        int count = 0;
    };
    Line line(float eta, float alpha) const;
    /// T at μ = cosTheta on a prepared line (Catmull-Rom in μ).
    float transmittance(const Line& l, float cosTheta) const;

    /// T(η, α, μ) by tricubic Catmull-Rom interpolation (eq. 2.44); arguments are clamped to
    /// the domain. T12 = transmittance(η, α, cosθi), T21 = transmittance(η, α, cosθo)
    /// (eqs. 2.52–2.53). Same as transmittance(line(η, α), μ).
    float transmittance(float eta, float alpha, float cosTheta) const { return transmittance(line(eta, alpha), cosTheta); }
    /// Td(η, α) by bicubic Catmull-Rom interpolation (eq. 2.51); Fdr = 1 − Td (eq. 2.54).
    float internalDiffuseTransmittance(float eta, float alpha) const;

    /// Grid node values (for tests).
    static float etaNode(int i, int n) { return kEtaMin + (kEtaMax - kEtaMin) * sqr(float(i) / float(n - 1)); }
    static float alphaNode(int i, int n) { return kAlphaMax * sqr(float(i) / float(n - 1)); }
    static float muNode(int i, int n) { return float(i) / float(n - 1); }
};

/// Brute-force directional transmittance T(η, α, μ) (double-precision quadrature with `q` points
/// per dimension and piece). η may be < 1 (light inside the denser medium; total internal
/// reflection then removes the corresponding microfacets). α = 0 gives the smooth 1 − F.
double roughTransmittanceIntegral(MicrofacetType type, double eta, double alpha, double mu, int q = 24);
/// Brute-force Td(η, α) = (1/η²) 2∫ T(η, α, μ) μ dμ (Gauss-Legendre in μ, `qMu` points).
double roughInternalDiffuseIntegral(MicrofacetType type, double eta, double alpha, int q = 24, int qMu = 32);

/// Compute all tables (parallel).
RoughTransmittanceTables buildRoughTables(MicrofacetType type, const RoughTableResolution& res);

/// Disk cache: read (returns nullopt and sets *why for a missing, truncated, corrupt or
/// mismatching file) and write (atomically: temporary file + rename; false on failure).
std::optional<RoughTransmittanceTables> readRoughTables(const std::string& path, MicrofacetType type,
                                                        const RoughTableResolution& res, std::string* why);
bool writeRoughTables(const std::string& path, const RoughTransmittanceTables& t);
/// Load from `path` or build (and write) them; a corrupt file gives a warning on stderr and a rebuild.
RoughTransmittanceTables loadOrBuildRoughTables(const std::string& path, MicrofacetType type,
                                                const RoughTableResolution& res);

/// Cache directory (IRIS_CACHE_DIR, else $XDG_CACHE_HOME/iris, else $HOME/.cache/iris) and the
/// file name keyed by the distribution, resolution, quadrature and format version.
std::string roughTablesCacheDir();
std::string roughTablesCachePath(MicrofacetType type, const RoughTableResolution& res);

/// The process-wide tables of a distribution: built or loaded on the first call (thread-safe),
/// then shared. Only rough-plastic-type materials call this.
const RoughTransmittanceTables& roughPlasticTables(MicrofacetType type);

/// How many times the process-wide tables were acquired (loaded or built), per distribution
/// (index 0 Beckmann, 1 GGX); for tests that check laziness.
int roughPlasticTablesAcquired(MicrofacetType type);

}  // namespace iris
