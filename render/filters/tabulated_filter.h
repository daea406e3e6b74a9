// Sampling of any separable filter profile by tabulation: |f| is tabulated at kSegments equal
// segments of [−r, r] (midpoint values), a segment is chosen from their discrete CDF and the offset
// is uniform within it; the weight is the sign of f there times ∫|f| / ∫f (Ernst et al. 2006, §3).
// The sampled filter is the piecewise-constant approximation of f with 1024 segments per axis.
#pragma once

#include <functional>
#include <vector>

#include "render/filters/rfilter.h"

namespace iris {

class TabulatedFilter : public ReconstructionFilter {
public:
    static constexpr int kSegments = 1024;
    float radius() const override { return radius_; }
    float eval(float x) const override { return std::abs(x) <= radius_ ? profile_(x) : 0.0f; }
    FilterSample sample(const vec2& u) const override;

protected:
    TabulatedFilter(float radius, std::function<float(float)> profile);

private:
    /// One axis: the offset, and the sign of f there (±1).
    float sample1D(float u, float& sign) const;
    float radius_;
    std::function<float(float)> profile_;
    std::vector<float> cdf_;    // kSegments + 1 entries, cdf_[0] = 0, cdf_.back() = 1
    std::vector<float> sign_;   // sign of f on each segment
    float norm_ = 1.0f;         // ∫|f| / ∫f over one axis
};

}  // namespace iris
