#include "render/filters/tabulated_filter.h"

#include <algorithm>

namespace iris {

TabulatedFilter::TabulatedFilter(float radius, std::function<float(float)> profile)
    : radius_(radius), profile_(std::move(profile)) {
    if (!(radius_ > 0) || !std::isfinite(radius_)) fail("filter radius must be positive, got ", radius_);
    cdf_.assign(kSegments + 1, 0.0f);
    sign_.assign(kSegments, 1.0f);
    const double h = 2.0 * radius_ / kSegments;
    double absSum = 0.0, signedSum = 0.0;
    std::vector<double> cdf(kSegments + 1, 0.0);
    for (int i = 0; i < kSegments; ++i) {
        const double f = profile_(float(-radius_ + (i + 0.5) * h));  // midpoint rule
        sign_[i] = f < 0 ? -1.0f : 1.0f;
        absSum += std::abs(f);
        signedSum += f;
        cdf[i + 1] = absSum;
    }
    if (!(signedSum > 0)) fail("filter profile integrates to ", signedSum * h, " (must be positive)");
    for (int i = 0; i <= kSegments; ++i) cdf_[i] = float(cdf[i] / absSum);
    cdf_.back() = 1.0f;
    norm_ = float(absSum / signedSum);
}

float TabulatedFilter::sample1D(float u, float& sign) const {
    // First segment whose CDF exceeds u (segments of zero mass are never chosen).
    const auto it = std::upper_bound(cdf_.begin() + 1, cdf_.end(), u);
    const int i = std::min(int(it - cdf_.begin()) - 1, kSegments - 1);
    const float width = cdf_[i + 1] - cdf_[i];
    const float t = width > 0 ? std::clamp((u - cdf_[i]) / width, 0.0f, 1.0f) : 0.5f;
    sign = sign_[i];
    return -radius_ + (float(i) + t) * (2.0f * radius_ / kSegments);
}

FilterSample TabulatedFilter::sample(const vec2& u) const {
    float sx, sy;
    const vec2 offset(sample1D(u.x, sx), sample1D(u.y, sy));
    return {offset, sx * sy * norm_ * norm_};
}

}  // namespace iris
