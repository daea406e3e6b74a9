// Reconstruction filters (Mitsuba's <rfilter>): a separable profile f(x) f(y) in pixels, applied by
// filter importance sampling (Ernst, Stamminger & Greiner, "Filter Importance Sampling", RT 2006):
// each sample lands at a film offset drawn with density ∝ |f(x) f(y)| and carries the weight
// sign(f(x) f(y)) · (∫|f| / ∫f)², so the mean of a pixel's weighted samples is the image convolved
// with the normalised filter, and every sample stays in one pixel (render/film.h).
#pragma once

#include <memory>
#include <string>

#include "core/math.h"
#include "core/registry.h"

namespace iris {

/// A film offset in pixels and the sample's weight (1 for filters without negative lobes).
struct FilterSample {
    vec2 offset{0.0f};
    float weight = 1.0f;
};

class ReconstructionFilter {
public:
    virtual ~ReconstructionFilter() = default;
    /// Half-width of the support in pixels: f(x) = 0 for |x| > radius().
    virtual float radius() const = 0;
    /// The 1D profile f(x), not normalised.
    virtual float eval(float x) const = 0;
    /// An offset drawn from |f(x) f(y)| with its weight (see the header comment); u in [0,1)².
    virtual FilterSample sample(const vec2& u) const = 0;
};

using ReconstructionFilterPtr = std::shared_ptr<const ReconstructionFilter>;
using RFilterRegistry = Registry<ReconstructionFilter>;

/// A filter of the given type with its default parameters (for scenes built in code).
ReconstructionFilterPtr makeFilter(const std::string& type);

}  // namespace iris
