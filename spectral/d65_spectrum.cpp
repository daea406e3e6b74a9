#include "spectral/d65_spectrum.h"

#include "core/error.h"
#include "spectral/cie.h"
#include "spectral/cie_tables.h"
#include "spectral/color_space.h"

namespace iris {

D65Spectrum::D65Spectrum(float scale) : Spectrum(SpectrumKind::Illuminant) {
    if (!std::isfinite(scale)) fail("D65 scale must be finite, got ", scale);
    k_ = float(double(scale) * d65YNormalisation());
    float m = 0;
    for (int i = 0; i < cie::tables::kD65Count; ++i) m = std::max(m, cie::tables::kD65[i]);
    max_ = k_ >= 0 ? k_ * m : 0.0f;
    rgb_ = rgbProjection([this](float l) { return eval(l); }, SpectrumKind::Illuminant);
}

float D65Spectrum::eval(float lambda) const { return k_ * cie::d65(lambda); }

SampledSpectrum D65Spectrum::sample(const SampledWavelengths& wl) const {
    if (wl.isRGB()) return Spectrum::sample(wl);  // the RGB projection, as for every illuminant
    SampledSpectrum s(wl.size());
    const float* d65 = wl.d65Lanes();
    float* v = s.lanes();
    for (int i = 0; i < SampledSpectrum::paddedSize(wl.size()); ++i) v[i] = k_ * d65[i];
    return s;
}

}  // namespace iris
