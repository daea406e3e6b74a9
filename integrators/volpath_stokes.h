// The polarized parts of `volpath` and `volpathmis` (docs/polarization.md; integrators/volpath.cpp
// runs one algorithm for spectra and for Stokes vectors): a scattering vertex's Mueller matrix with
// its world-space bases, the Mueller matrix a shadow ray collects crossing pass-through surfaces,
// and the contribution of a light sample through both. Emitters are unpolarized (Mitsuba 3).
#pragma once

#include "integrators/stokes_throughput.h"
#include "materials/material.h"
#include "media/phase/phase_function.h"

namespace iris {

/// A vertex's matrix for light arriving along −wi (basis `inBasis`) and leaving along wo (basis
/// `outBasis`), world space.
struct VertexMueller {
    MuellerSpectrum M;
    vec3 wi{0.0f}, inBasis{0.0f}, outBasis{0.0f};
};
/// The BSDF's matrix towards wiLocal (cos θi included), local frame `frame`.
VertexMueller surfaceMueller(const BSDF& bsdf, const Frame& frame, const vec3& woLocal, const vec3& wiLocal);
/// The phase function's matrix at x (world directions).
VertexMueller phaseMueller(const PhaseFunction& phase, const vec3& x, const vec3& wo, const vec3& wi, int n);

/// The transmittance of a shadow ray as the Mueller matrix of what it crossed, light → vertex, in
/// the basis stokesBasis(forward), forward = −(shadow ray direction), the way the light travels.
class ShadowMueller {
public:
    ShadowMueller(int n, const vec3& shadowDir);
    static ShadowMueller zero(int n, const vec3& shadowDir);
    void operator*=(const SampledSpectrum& s) { M_ *= s; }
    void operator/=(float q) { M_ *= 1.0f / q; }
    /// The largest unpolarized weight (ratio tracking's Russian roulette).
    float maxValue() const { return M_.expanded()(0, 0).maxValue(); }
    bool isBlack() const { return M_.expanded()(0, 0).isBlack(); }
    /// A crossed surface's pass-through matrix `local` (BSDF::nullTransmissionMueller, local frame f).
    void cross(const MuellerSpectrum& local, const Frame& f);
    /// The Stokes vector unpolarized radiance L becomes on its way to the vertex, in basis().
    StokesVector arriving(const SampledSpectrum& L) const;
    const vec3& basis() const { return basis_; }
    const vec3& forward() const { return forward_; }

private:
    MuellerSpectrum M_;
    vec3 forward_, basis_;
};

/// rows · v.M · (the light's Stokes vector through `shadow`) · w added to est (the rows' basis is
/// v.outBasis: the caller changed it to the vertex's output basis).
void addLightThrough(const StokesThroughput& rows, const VertexMueller& v, const ShadowMueller& shadow, const SampledSpectrum& L,
                     float w, StokesVector& est);

}  // namespace iris
