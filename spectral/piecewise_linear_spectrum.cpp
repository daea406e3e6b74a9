#include "spectral/piecewise_linear_spectrum.h"

#include "core/error.h"
#include "spectral/color_space.h"

namespace iris {

PiecewiseLinearSpectrum::PiecewiseLinearSpectrum(std::vector<float> lambdas, std::vector<float> values, SpectrumKind kind)
    : Spectrum(kind), lambdas_(std::move(lambdas)), values_(std::move(values)) {
    if (lambdas_.empty()) fail("piecewise-linear spectrum: no (wavelength, value) pairs");
    if (lambdas_.size() != values_.size())
        fail("piecewise-linear spectrum: ", lambdas_.size(), " wavelengths but ", values_.size(), " values");
    for (size_t i = 0; i < lambdas_.size(); ++i) {
        if (!std::isfinite(lambdas_[i]) || !std::isfinite(values_[i]))
            fail("piecewise-linear spectrum: non-finite entry ", i, " (", lambdas_[i], " nm, ", values_[i], ")");
        if (i > 0 && !(lambdas_[i] > lambdas_[i - 1]))
            fail("piecewise-linear spectrum: wavelengths must be strictly increasing (", lambdas_[i - 1], " nm then ",
                 lambdas_[i], " nm)");
    }
    // Constant extrapolation, so the maximum over [360, 830] is at most the largest sample.
    max_ = *std::max_element(values_.begin(), values_.end());
    rgb_ = rgbProjection([this](float l) { return eval(l); }, kind);
}

float PiecewiseLinearSpectrum::eval(float lambda) const {
    if (lambda <= lambdas_.front()) return values_.front();
    if (lambda >= lambdas_.back()) return values_.back();
    // First sample strictly above lambda; lambda lies in [i−1, i).
    const size_t i = size_t(std::upper_bound(lambdas_.begin(), lambdas_.end(), lambda) - lambdas_.begin());
    const float t = (lambda - lambdas_[i - 1]) / (lambdas_[i] - lambdas_[i - 1]);
    return (1.0f - t) * values_[i - 1] + t * values_[i];
}

}  // namespace iris
