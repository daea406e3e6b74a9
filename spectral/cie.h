// CIE colorimetric data: the CIE 1931 2° colour matching functions (1 nm, 360–830 nm) and
// standard illuminant D65, both from the published CIE tables (CIE 015:2018; see cie_tables.cpp).
// Outside [360, 830] nm every function returns 0.
#pragma once

#include "core/math.h"

namespace iris::cie {

/// (x̄, ȳ, z̄)(λ), linear interpolation of the 1 nm table.
vec3 xyzBar(float lambda);
float xBar(float lambda);
float yBar(float lambda);
float zBar(float lambda);

/// CIE standard illuminant D65 relative SPD (100 at 560 nm), linear interpolation of the 5 nm table
/// (which is how the CIE's own 1 nm table is defined).
float d65(float lambda);

/// d65 for `count` wavelengths at once (count a multiple of 4, e.g. SampledSpectrum::paddedSize(n)):
/// out[j] = d65(lambda[j]), bit-identical to the one-wavelength lookup (tests/spectral/test_spectral_lanes.cpp),
/// written as loops over lanes that the compiler vectorises (the table reads stay scalar loads).
void d65Lanes(const float* lambda, int count, float* out);

/// Σ_{j<n} weight[j] · xyzBar(lambda[j]), summed in the order j = 0, 1, … per component: the
/// value of that plain loop, bit for bit (tests/spectral/test_spectral_lanes.cpp). lambda and weight must
/// be readable up to n rounded up to a multiple of 4 (lanes of SampledWavelengths and
/// SampledSpectrum are).
vec3 weightedXyzBarSum(const float* lambda, const float* weight, int n);

/// ∫ ȳ(λ) dλ over the table (1 nm rectangle rule on the 1 nm samples, in nm): ≈ 106.857.
/// Y is normalised by it: Y = ∫ L ȳ dλ / ∫ ȳ dλ, so a constant spectrum 1 has Y = 1.
double yIntegral();

/// Every table wavelength (nm) visited by the 1 nm quadrature used throughout: 360, 361, …, 830.
constexpr int kQuadratureFirst = 360;
constexpr int kQuadratureLast = 830;

}  // namespace iris::cie
