// A spectrum tabulated at arbitrary increasing wavelengths, linearly interpolated, constant
// outside the table (measured data: .spd files, <spectrum value="λ:v, ..."/>).
#pragma once

#include <vector>

#include "spectral/spectrum.h"

namespace iris {

class PiecewiseLinearSpectrum final : public Spectrum {
public:
    /// lambdas strictly increasing (nm), same size as values, non-empty, all finite; else iris::Error.
    PiecewiseLinearSpectrum(std::vector<float> lambdas, std::vector<float> values, SpectrumKind kind);

    float eval(float lambda) const override;
    float maxValue() const override { return max_; }
    vec3 rgbValue() const override { return rgb_; }

    const std::vector<float>& lambdas() const { return lambdas_; }
    const std::vector<float>& values() const { return values_; }

private:
    std::vector<float> lambdas_, values_;
    float max_ = 0;
    vec3 rgb_{0.0f};
};

}  // namespace iris
