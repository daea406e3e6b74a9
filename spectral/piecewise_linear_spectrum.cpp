#include "spectral/piecewise_linear_spectrum.h"

#include "core/error.h"
#include "spectral/color_space.h"

namespace iris {

PiecewiseLinearSpectrum::PiecewiseLinearSpectrum(std::vector<float> lambdas, std::vector<float> values, SpectrumKind kind)
    : Spectrum(kind), zeroOutside_(kind != SpectrumKind::Unbounded), lambdas_(std::move(lambdas)), values_(std::move(values)) {
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
    // Buckets: about four per table interval, so the walk from a bucket's start is a step or two.
    if (lambdas_.size() >= 2) {
        const size_t buckets = std::min<size_t>(4 * lambdas_.size(), 4096);
        bucketScale_ = float(double(buckets) / (double(lambdas_.back()) - double(lambdas_.front())));
        bucketStart_.resize(buckets);
        for (size_t b = 0; b < buckets; ++b) {
            const float edge = lambdas_.front() + float(b) / bucketScale_;
            bucketStart_[b] =
                uint32_t(std::upper_bound(lambdas_.begin(), lambdas_.end(), edge) - lambdas_.begin());
        }
    }
    // Zero or constant extrapolation: the maximum over [360, 830] is at most the largest sample (or 0).
    max_ = *std::max_element(values_.begin(), values_.end());
    if (zeroOutside_) max_ = std::max(max_, 0.0f);
    rgb_ = rgbProjection([this](float l) { return eval(l); }, kind);
}

float PiecewiseLinearSpectrum::eval(float lambda) const {
    if (std::isnan(lambda)) return lambda;  // (the binary search used to read past the end)
    if (zeroOutside_ && (lambda < lambdas_.front() || lambda > lambdas_.back())) return 0.0f;
    if (lambda <= lambdas_.front()) return values_.front();
    if (lambda >= lambdas_.back()) return values_.back();
    // First sample strictly above lambda; lambda lies in [i−1, i).
    const size_t i = upperIndex(lambda);
    const float t = (lambda - lambdas_[i - 1]) / (lambdas_[i] - lambdas_[i - 1]);
    return (1.0f - t) * values_[i - 1] + t * values_[i];
}

size_t PiecewiseLinearSpectrum::upperIndex(float lambda) const {
    // lambda is strictly inside (front, back) and the table has two or more samples. The bucket
    // only chooses where to start: walking back while the previous sample is above lambda and
    // forward while the current one is not gives lambdas_[i−1] <= lambda < lambdas_[i], the
    // index of std::upper_bound, whatever the rounding of the bucket computation.
    const size_t last = bucketStart_.size() - 1;
    const float b = (lambda - lambdas_.front()) * bucketScale_;
    size_t i = bucketStart_[std::min(size_t(std::max(b, 0.0f)), last)];
    while (i > 1 && lambdas_[i - 1] > lambda) --i;
    while (lambdas_[i] <= lambda) ++i;
    return i;
}

}  // namespace iris
