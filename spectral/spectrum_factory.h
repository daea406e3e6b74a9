// Constructors for every kind of spectrum a scene can specify. Implemented in spectral/*.cpp.
#pragma once

#include <string>
#include <vector>

#include "spectral/spectrum.h"

namespace iris {

/// Spectrum from a linear Rec.709 RGB triple. Reflectance: Jakob & Hanika 2019 sigmoid-polynomial
/// upsampling, bounded in [0,1]. Unbounded: scaled sigmoid (value max(rgb)·s(λ)). Illuminant:
/// sigmoid × CIE D65 normalised so that RGB (1,1,1) emits the D65 white point (see
/// docs/conventions.md). In RGB mode all three return `rgb` unchanged.
SpectrumPtr makeRGBSpectrum(const vec3& rgb, SpectrumKind kind);

/// Piecewise-linear spectrum through (lambda[i], value[i]), lambda strictly increasing (nm);
/// constant extrapolation outside the range. Throws iris::Error on malformed input.
SpectrumPtr makePiecewiseLinearSpectrum(std::vector<float> lambdas, std::vector<float> values, SpectrumKind kind);

/// Planck blackbody radiance at temperature T (K), normalised to peak 1, times scale (Illuminant).
SpectrumPtr makeBlackbodySpectrum(float temperatureK, float scale = 1.0f);

/// CIE standard illuminant D65, normalised so that its luminance Y is 1, times scale (Illuminant).
SpectrumPtr makeD65Spectrum(float scale = 1.0f);

/// Read a ".spd" file: lines "lambda value", '#' comments. Wavelengths in nm (values below 100
/// are read as micrometres and converted). Throws iris::Error naming the file and line.
SpectrumPtr loadSpdFile(const std::string& path, SpectrumKind kind);

}  // namespace iris
