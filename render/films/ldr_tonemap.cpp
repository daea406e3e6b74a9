#include "render/films/ldr_tonemap.h"

#include <algorithm>
#include <cmath>

namespace iris {

namespace {

float luminance(const float* c) { return 0.2126f * c[0] + 0.7152f * c[1] + 0.0722f * c[2]; }  // Rec.709 Y

float encode(float v, float gamma) {
    v = std::clamp(v, 0.0f, 1.0f);
    if (gamma > 0) return std::pow(v, 1.0f / gamma);
    return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;  // IEC 61966-2-1
}

/// Reinhard et al. 2002: L = a / L̄w · Lw with the log-average L̄w (eq. 1–2), Ld = L (1 + L / Lwhite²)
/// / (1 + L) (eq. 4); Lwhite is the largest scaled luminance times (1 − burn) (iris's reading of
/// Mitsuba 0.6's reinhardBurn). Colours are scaled by Ld / Lw.
void reinhard(const LdrSettings& s, float* rgb, size_t n) {
    double logSum = 0;
    float maxY = 0;
    for (size_t i = 0; i < n; ++i) {
        const float y = std::max(luminance(rgb + 3 * i), 0.0f);
        logSum += std::log(1e-4 + y);
        maxY = std::max(maxY, y);
    }
    if (n == 0 || !(maxY > 0)) return;
    const float scale = s.key / float(std::exp(logSum / double(n)));
    const float white = std::max(1e-6f, maxY * scale * (1.0f - std::clamp(s.burn, 0.0f, 1.0f)));
    for (size_t i = 0; i < n; ++i) {
        float* c = rgb + 3 * i;
        const float y = luminance(c);
        if (!(y > 0)) continue;
        const float l = scale * y, ld = l * (1.0f + l / (white * white)) / (1.0f + l);
        for (int k = 0; k < 3; ++k) c[k] *= ld / y;
    }
}

}  // namespace

void applyLdrTonemap(const LdrSettings& s, float* rgb, size_t n) {
    const float m = std::exp2(s.exposure);
    for (size_t i = 0; i < 3 * n; ++i) rgb[i] *= m;
    if (s.method == LdrSettings::Method::Reinhard) reinhard(s, rgb, n);
    for (size_t i = 0; i < 3 * n; ++i) rgb[i] = encode(rgb[i], s.gamma);
}

}  // namespace iris
