#include "materials/albedo.h"

#include <algorithm>
#include <cmath>

#include "core/rng.h"

namespace iris {

AlbedoEstimate albedoFromSums(double sum, double sumSq, int n) {
    AlbedoEstimate e;
    e.mean = sum / n;
    const double var = std::max(0.0, sumSq / n - e.mean * e.mean);  // population variance of the values
    e.stderr_ = std::sqrt(var / std::max(1, n - 1));
    return e;
}

std::vector<AlbedoEstimate> directionalAlbedo(const BSDF& bsdf, const vec3& wo, int samples, uint64_t seed,
                                              TransportMode mode) {
    Pcg32 rng(mix64(seed), mix64(seed ^ 0x5851f42d4c957f2dull));
    std::vector<double> s, s2;
    for (int i = 0; i < samples; ++i) {
        const float uc = rng.uniform();
        const float u0 = rng.uniform();
        const vec2 u(u0, rng.uniform());
        const auto smp = bsdf.sample(wo, uc, u, mode);
        if (!smp) continue;
        const SampledSpectrum w = smp->weight();
        if (s.empty()) {
            s.assign(w.size(), 0.0);
            s2.assign(w.size(), 0.0);
        }
        for (int c = 0; c < w.size(); ++c) {
            s[c] += w[c];
            s2[c] += double(w[c]) * w[c];
        }
    }
    std::vector<AlbedoEstimate> out;
    for (size_t c = 0; c < s.size(); ++c) out.push_back(albedoFromSums(s[c], s2[c], samples));
    return out;
}

}  // namespace iris
