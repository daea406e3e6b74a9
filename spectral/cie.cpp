#include "spectral/cie.h"

#include "spectral/cie_tables.h"

namespace iris::cie {

namespace {
using namespace tables;

// Linear interpolation in a table with samples at first + i*step (nm); 0 outside.
float interpolate(const float* table, int count, float first, float step, float lambda) {
    const float x = (lambda - first) / step;
    if (!(x >= 0.0f) || x > float(count - 1)) return 0.0f;
    const int i = std::min(int(x), count - 2);
    const float t = x - float(i);
    return (1.0f - t) * table[i] + t * table[i + 1];
}

double computeYIntegral() {
    double s = 0.0;
    for (int i = 0; i < kCmfCount; ++i) s += kYBar[i];  // × 1 nm
    return s;
}
}  // namespace

float xBar(float lambda) { return interpolate(kXBar, kCmfCount, float(kCmfFirst), 1.0f, lambda); }
float yBar(float lambda) { return interpolate(kYBar, kCmfCount, float(kCmfFirst), 1.0f, lambda); }
float zBar(float lambda) { return interpolate(kZBar, kCmfCount, float(kCmfFirst), 1.0f, lambda); }

vec3 xyzBar(float lambda) {
    const float x = lambda - float(kCmfFirst);
    if (!(x >= 0.0f) || x > float(kCmfCount - 1)) return vec3(0.0f);
    const int i = std::min(int(x), kCmfCount - 2);
    const float t = x - float(i);
    return vec3((1.0f - t) * kXBar[i] + t * kXBar[i + 1], (1.0f - t) * kYBar[i] + t * kYBar[i + 1],
                (1.0f - t) * kZBar[i] + t * kZBar[i + 1]);
}

float d65(float lambda) { return interpolate(kD65, kD65Count, float(kD65First), float(kD65Step), lambda); }

double yIntegral() {
    static const double v = computeYIntegral();
    return v;
}

}  // namespace iris::cie
