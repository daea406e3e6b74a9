// Tent filter (Mitsuba "tent"): f(x) = max(0, 1 − |x| / r), radius r = 1 px by default.
#include "render/filters/tabulated_filter.h"

namespace iris {

namespace {

class TentFilter final : public TabulatedFilter {
public:
    explicit TentFilter(float r) : TabulatedFilter(r, [r](float x) { return std::max(0.0f, 1.0f - std::abs(x) / r); }) {}
};

std::shared_ptr<ReconstructionFilter> createTent(const Properties& p) {
    const float r = p.getFloat("radius", 1.0f);
    if (!(r > 0) || !std::isfinite(r)) failAt(p.locationOf("radius"), "tent filter radius must be positive");
    return std::make_shared<TentFilter>(r);
}

}  // namespace

IRIS_REGISTER(RFilterRegistry, "tent", createTent);

}  // namespace iris
