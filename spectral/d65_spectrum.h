// CIE standard illuminant D65 scaled so that its luminance Y is 1 (times a scale factor).
#pragma once

#include "spectral/spectrum.h"

namespace iris {

class D65Spectrum final : public Spectrum {
public:
    explicit D65Spectrum(float scale = 1.0f);
    float eval(float lambda) const override;
    /// eval at the path's wavelengths from the D65 values cached with them (the same values).
    SampledSpectrum sample(const SampledWavelengths& wl) const override;
    float maxValue() const override { return max_; }
    vec3 rgbValue() const override { return rgb_; }

private:
    float k_;  // scale · ∫ȳ / ∫ D65 ȳ
    float max_;
    vec3 rgb_;
};

}  // namespace iris
