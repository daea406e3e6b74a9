#include "spectral/rgb_spectrum_grid.h"

#include <tbb/parallel_for.h>

#include <atomic>
#include <optional>

#include "spectral/cie.h"
#include "spectral/color_space.h"

namespace iris {

namespace {
constexpr int K = RGBSpectrumGrid::kResolution;
std::atomic<bool> gBuilt{false};
}  // namespace

RGBSpectrumGrid::RGBSpectrumGrid() {
    // Fit the nodes in parallel into optional slots, then move them into place in index order.
    std::vector<std::optional<RGBSpectrum>> fitted(size_t(K) * K * K);
    tbb::parallel_for(0, K * K * K, [&](int i) {
        const int r = i / (K * K), g = (i / K) % K, b = i % K;
        fitted[size_t(i)].emplace(vec3(float(r), float(g), float(b)) / float(K - 1), SpectrumKind::Reflectance);
    });
    nodes_.reserve(fitted.size());
    for (auto& f : fitted) nodes_.push_back(std::move(*f));
    gBuilt.store(true, std::memory_order_release);
}

const RGBSpectrumGrid& RGBSpectrumGrid::instance() {
    static const RGBSpectrumGrid grid;
    return grid;
}

bool RGBSpectrumGrid::built() { return gBuilt.load(std::memory_order_acquire); }

RGBSpectrumGrid::Cell RGBSpectrumGrid::cell(const vec3& rgbIn) const {
    const vec3 p = glm::clamp(rgbIn, 0.0f, 1.0f) * float(K - 1);
    int i0[3];
    float f[3];
    for (int a = 0; a < 3; ++a) {
        i0[a] = std::min(int(p[a]), K - 2);
        f[a] = p[a] - float(i0[a]);
    }
    Cell c;
    for (int corner = 0; corner < 8; ++corner) {
        float w = 1.0f;
        int idx[3];
        for (int a = 0; a < 3; ++a) {
            const int bit = (corner >> (2 - a)) & 1;
            idx[a] = i0[a] + bit;
            w *= bit ? f[a] : 1.0f - f[a];
        }
        c.node[corner] = &nodes_[size_t((idx[0] * K + idx[1]) * K + idx[2])];
        c.weight[corner] = w;
    }
    return c;
}

SampledSpectrum RGBSpectrumGrid::reflectance(const vec3& rgb, const SampledWavelengths& wl) const {
    const Cell c = cell(rgb);
    SampledSpectrum s(wl.size(), 0.0f);
    for (int k = 0; k < 8; ++k) {
        if (c.weight[k] == 0.0f) continue;
        for (int i = 0; i < wl.size(); ++i) s[i] += c.weight[k] * c.node[k]->eval(wl.lambda(i));
    }
    return s;
}

float RGBSpectrumGrid::reflectance(const vec3& rgb, float lambda) const {
    const Cell c = cell(rgb);
    float v = 0.0f;
    for (int k = 0; k < 8; ++k)
        if (c.weight[k] != 0.0f) v += c.weight[k] * c.node[k]->eval(lambda);
    return v;
}

SampledSpectrum RGBSpectrumGrid::sample(const vec3& rgb, SpectrumKind kind, const SampledWavelengths& wl) const {
    if (wl.isRGB()) {
        SampledSpectrum s(3);
        for (int i = 0; i < 3; ++i) s[i] = rgb[i];
        return s;
    }
    if (kind == SpectrumKind::Reflectance) return reflectance(rgb, wl);
    const vec3 c = glm::max(rgb, vec3(0.0f));
    const float m = std::max({c.x, c.y, c.z});
    if (m <= 0.0f) return SampledSpectrum(wl.size(), 0.0f);
    SampledSpectrum s = reflectance(c / m, wl) * m;
    if (kind == SpectrumKind::Illuminant) {
        const float k = float(d65YNormalisation());
        for (int i = 0; i < wl.size(); ++i) s[i] *= k * cie::d65(wl.lambda(i));
    }
    return s;
}

}  // namespace iris
