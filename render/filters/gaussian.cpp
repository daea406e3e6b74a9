// Gaussian filter (Mitsuba "gaussian", stddev 0.5 px by default), truncated at 3 stddev. Sampled
// per axis through a tabulated inverse CDF (1025 entries, linear interpolation; exact at its nodes
// to float precision).
#include "render/filters/rfilter.h"

#include <vector>

namespace iris {

namespace {

class GaussianFilter final : public ReconstructionFilter {
public:
    explicit GaussianFilter(float stddev);
    float radius() const override { return 3.0f * stddev_; }
    float eval(float x) const override {
        return std::abs(x) <= radius() ? std::exp(-0.5f * x * x / (stddev_ * stddev_)) : 0.0f;
    }
    FilterSample sample(const vec2& u) const override { return {vec2(sample1D(u.x), sample1D(u.y)), 1.0f}; }

private:
    float sample1D(float u) const;
    float stddev_;
    std::vector<float> inverseCdf_;
};

GaussianFilter::GaussianFilter(float stddev) : stddev_(stddev) {
    // Truncated Gaussian on [−3σ, 3σ]: CDF(x) = (erf(x/(σ√2)) + erf(a/(σ√2))) / (2 erf(a/(σ√2))).
    // Invert at 1025 evenly spaced probabilities by Newton's method on erf (in double).
    const int n = 1025;
    const double a = 3.0 * stddev_, s = stddev_ * std::sqrt(2.0), ea = std::erf(a / s);
    inverseCdf_.resize(n);
    for (int i = 0; i < n; ++i) {
        const double target = (2.0 * i / (n - 1) - 1.0) * ea;  // erf(x/s) = target
        double x = 0.0;
        for (int it = 0; it < 50; ++it) {
            const double f = std::erf(x / s) - target;
            const double df = 2.0 / std::sqrt(M_PI) * std::exp(-(x / s) * (x / s)) / s;
            const double next = std::clamp(x - f / df, -a, a);
            if (std::abs(next - x) < 1e-12) break;
            x = next;
        }
        inverseCdf_[i] = float(x);
    }
    inverseCdf_.front() = float(-a);
    inverseCdf_.back() = float(a);
}

float GaussianFilter::sample1D(float u) const {
    const float t = u * float(inverseCdf_.size() - 1);
    const int i = std::min(int(t), int(inverseCdf_.size()) - 2);
    const float f = t - float(i);
    return (1.0f - f) * inverseCdf_[i] + f * inverseCdf_[i + 1];
}

std::shared_ptr<ReconstructionFilter> createGaussian(const Properties& p) {
    const float stddev = p.getFloat("stddev", 0.5f);
    if (!(stddev > 0)) failAt(p.locationOf("stddev"), "gaussian filter stddev must be positive");
    return std::make_shared<GaussianFilter>(stddev);
}

}  // namespace

IRIS_REGISTER(RFilterRegistry, "gaussian", createGaussian);

}  // namespace iris
