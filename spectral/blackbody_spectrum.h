// Planck blackbody emitter, normalised to peak 1 and multiplied by a scale (Illuminant).
#pragma once

#include "spectral/spectrum.h"

namespace iris {

/// Planck's law spectral radiance B(λ, T) in W·sr⁻¹·m⁻³ (λ in nm, T in K).
double planck(double lambdaNm, double temperatureK);

class BlackbodySpectrum final : public Spectrum {
public:
    /// temperatureK > 0 and finite, else iris::Error.
    BlackbodySpectrum(float temperatureK, float scale);
    float eval(float lambda) const override;
    float maxValue() const override { return scale_; }
    vec3 rgbValue() const override { return rgb_; }
    float temperature() const { return T_; }

private:
    float T_, scale_;
    double invPeak_ = 1;
    vec3 rgb_{0.0f};
};

}  // namespace iris
