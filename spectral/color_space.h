// Construction-time colour conversions of spectra (NOT the image output path, which goes through
// OpenColorIO, spectral/color_management.h):
//   - XYZ ↔ linear Rec.709 with the IEC 61966-2-1 (sRGB) matrices, D65 white, no adaptation;
//   - rgbProjection(): the RGB-mode value of a spectrally defined spectrum (spectral/spectrum.h).
#pragma once

#include <functional>

#include "core/math.h"
#include "spectral/spectrum.h"

namespace iris {

/// XYZ → linear Rec.709, IEC 61966-2-1:1999 eq. (5): R = 3.2406X − 1.5372Y − 0.4986Z, ...
dvec3 xyzToLinearRec709(const dvec3& xyz);
/// Linear Rec.709 → XYZ, IEC 61966-2-1:1999 eq. (7): X = 0.4124R + 0.3576G + 0.1805B, ...
dvec3 linearRec709ToXYZ(const dvec3& rgb);

/// ∫ȳ dλ / ∫ D65 ȳ dλ: multiplying the CIE D65 table (100 at 560 nm) by this gives Y = 1.
double d65YNormalisation();

/// Linear Rec.709 RGB of the D65-lit reflectance ρ: RGB(ρ) = Σ_λ ρ(λ) w(λ), with the per-nm weights
/// w(λ) = M · D65(λ) cmf(λ) / Σ D65 ȳ (1 nm, 360…830 nm). ρ = 1 gives ≈ (1, 1, 1).
const dvec3* reflectanceRGBWeights();  // kReflectanceWeightCount entries, λ = 360 + i nm
constexpr int kReflectanceWeightCount = 471;

/// The RGB-mode value of a spectrum given as a function of wavelength:
///   Reflectance: RGB of the reflected D65 light, D65's Y normalised to 1 (so ρ = 1 → (1,1,1));
///   Illuminant: plain projection, XYZ = ∫ L cmf / ∫ ȳ, then the matrix above;
///   Unbounded: f at the default RGB channel wavelengths (defaultChannelWavelengths()).
vec3 rgbProjection(const std::function<float(float)>& f, SpectrumKind kind);

}  // namespace iris
