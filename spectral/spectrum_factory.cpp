// Factory functions of spectral/spectrum_factory.h; the classes live in their own files.
#include "spectral/spectrum_factory.h"

#include "spectral/blackbody_spectrum.h"
#include "spectral/d65_spectrum.h"
#include "spectral/piecewise_linear_spectrum.h"
#include "spectral/rgb_spectrum.h"

namespace iris {

SpectrumPtr makeRGBSpectrum(const vec3& rgb, SpectrumKind kind) { return std::make_shared<RGBSpectrum>(rgb, kind); }

SpectrumPtr makePiecewiseLinearSpectrum(std::vector<float> lambdas, std::vector<float> values, SpectrumKind kind) {
    return std::make_shared<PiecewiseLinearSpectrum>(std::move(lambdas), std::move(values), kind);
}

SpectrumPtr makeBlackbodySpectrum(float temperatureK, float scale) {
    return std::make_shared<BlackbodySpectrum>(temperatureK, scale);
}

SpectrumPtr makeD65Spectrum(float scale) { return std::make_shared<D65Spectrum>(scale); }

}  // namespace iris
