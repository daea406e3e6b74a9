// Box filter (Mitsuba "box", radius 0.5 px by default): f(x) = 1 on [−r, r].
#include "render/filters/rfilter.h"

namespace iris {

namespace {

class BoxFilter final : public ReconstructionFilter {
public:
    explicit BoxFilter(float r) : r_(r) {}
    float radius() const override { return r_; }
    float eval(float x) const override { return std::abs(x) <= r_ ? 1.0f : 0.0f; }
    FilterSample sample(const vec2& u) const override { return {(2.0f * u - vec2(1.0f)) * r_, 1.0f}; }

private:
    float r_;
};

std::shared_ptr<ReconstructionFilter> createBox(const Properties& p) {
    const float r = p.getFloat("radius", 0.5f);
    if (!(r > 0)) failAt(p.locationOf("radius"), "box filter radius must be positive");
    return std::make_shared<BoxFilter>(r);
}

}  // namespace

IRIS_REGISTER(RFilterRegistry, "box", createBox);

}  // namespace iris
