// Lanczos-windowed sinc filter (Mitsuba "lanczos"; Duchon, "Lanczos Filtering in One and Two
// Dimensions", J. Appl. Meteor. 1979): f(x) = sinc(πx) sinc(πx / a) for |x| < a, with a = lobes
// (default 3) the radius in pixels, as in Mitsuba 3 (src/rfilters/lanczos.cpp).
#include "render/filters/tabulated_filter.h"

namespace iris {

namespace {

float lanczos(float x, float a) {
    x = std::abs(x);
    if (x < 1e-6f) return 1.0f;
    if (x >= a) return 0.0f;
    const float px = kPi * x;
    return std::sin(px) * std::sin(px / a) / (px * px / a);
}

class LanczosFilter final : public TabulatedFilter {
public:
    explicit LanczosFilter(float a) : TabulatedFilter(a, [a](float x) { return lanczos(x, a); }) {}
};

std::shared_ptr<ReconstructionFilter> createLanczos(const Properties& p) {
    const int lobes = p.getInt("lobes", 3);
    if (lobes < 1 || lobes > 16) failAt(p.locationOf("lobes"), "lanczos lobes must be in 1..16");
    return std::make_shared<LanczosFilter>(float(lobes));
}

}  // namespace

IRIS_REGISTER(RFilterRegistry, "lanczos", createLanczos);

}  // namespace iris
