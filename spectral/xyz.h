// Spectrum → CIE 1931 XYZ. Normalisation (docs/conventions.md): Y = ∫ L ȳ dλ / ∫ ȳ dλ, so a
// constant spectrum 1 has XYZ ≈ (1, 1, 1) (illuminant E) and D65 scaled to Y = 1 has
// XYZ ≈ (0.9505, 1, 1.089).
#pragma once

#include "core/math.h"
#include "spectral/cie.h"
#include "spectral/sampled_spectrum.h"
#include "spectral/wavelengths.h"

namespace iris {

/// The film's Monte Carlo estimator of XYZ from one path's spectral radiance:
///   XYZ = (1/N) Σ_i L(λ_i) · cmf(λ_i) / pdf(λ_i) / ∫ȳ dλ,
/// skipping entries whose pdf is 0 (secondary wavelengths terminated by dispersion; the hero's pdf
/// was divided by N, which keeps the estimator unbiased). Spectral mode only: in RGB mode the
/// values already are linear Rec.709 and are not converted here.
vec3 toXYZ(const SampledSpectrum& L, const SampledWavelengths& wl);

/// Quadrature reference: XYZ of f(λ) by the 1 nm rectangle rule on the CIE table wavelengths
/// 360…830 nm, normalised by ∫ȳ dλ (same sum). f is any callable float(float lambda).
template <typename F>
dvec3 integrateXYZ(F&& f) {
    dvec3 s(0.0);
    for (int l = cie::kQuadratureFirst; l <= cie::kQuadratureLast; ++l)
        s += double(f(float(l))) * dvec3(cie::xyzBar(float(l)));
    return s / cie::yIntegral();
}

/// CIE 1931 chromaticity (x, y) of an XYZ triple.
inline dvec3 chromaticity(const dvec3& xyz) {
    const double s = xyz.x + xyz.y + xyz.z;
    return s != 0.0 ? dvec3(xyz.x / s, xyz.y / s, 0.0) : dvec3(0.0);
}

}  // namespace iris
