// Mitchell–Netravali cubic filters (Mitchell & Netravali, "Reconstruction Filters in Computer
// Graphics", SIGGRAPH 1988, eq. 8), radius 2 px as in Mitsuba 3 (src/rfilters/mitchell.cpp):
// "mitchell" with parameters B and C (default 1/3 each) and "catmullrom" (B = 0, C = 1/2).
#include "render/filters/tabulated_filter.h"

namespace iris {

namespace {

/// k(x) of Mitchell & Netravali eq. 8 for |x| < 2 (0 beyond).
float mitchellNetravali(float x, float B, float C) {
    x = std::abs(x);
    const float x2 = x * x, x3 = x2 * x;
    if (x < 1.0f) return ((12 - 9 * B - 6 * C) * x3 + (-18 + 12 * B + 6 * C) * x2 + (6 - 2 * B)) / 6.0f;
    if (x < 2.0f) return ((-B - 6 * C) * x3 + (6 * B + 30 * C) * x2 + (-12 * B - 48 * C) * x + (8 * B + 24 * C)) / 6.0f;
    return 0.0f;
}

class CubicFilter final : public TabulatedFilter {
public:
    CubicFilter(float B, float C) : TabulatedFilter(2.0f, [B, C](float x) { return mitchellNetravali(x, B, C); }) {}
};

std::shared_ptr<ReconstructionFilter> createMitchell(const Properties& p) {
    const float B = p.getFloat("B", 1.0f / 3.0f), C = p.getFloat("C", 1.0f / 3.0f);
    if (!std::isfinite(B) || !std::isfinite(C)) failAt(p.location(), "mitchell: B and C must be finite");
    return withLocation(p.location(), [&] { return std::make_shared<CubicFilter>(B, C); }, "mitchell: ");
}

std::shared_ptr<ReconstructionFilter> createCatmullRom(const Properties&) {
    return std::make_shared<CubicFilter>(0.0f, 0.5f);
}

}  // namespace

IRIS_REGISTER(RFilterRegistry, "mitchell", createMitchell);
IRIS_REGISTER(RFilterRegistry, "catmullrom", createCatmullRom);

}  // namespace iris
