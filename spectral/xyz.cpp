#include "spectral/xyz.h"

namespace iris {

vec3 toXYZ(const SampledSpectrum& L, const SampledWavelengths& wl) {
    assert(!wl.isRGB());
    // Monte Carlo estimate of ∫ L(λ) cmf(λ) dλ with N correlated (hero) samples, then divided
    // by ∫ȳ dλ (docs/conventions.md, "Spectral and colour conventions").
    vec3 sum(0.0f);
    const int n = wl.size();
    for (int i = 0; i < n; ++i) {
        const float pdf = wl.pdf(i);
        if (pdf == 0.0f) continue;
        sum += (L[i] / pdf) * cie::xyzBar(wl.lambda(i));
    }
    static const float invYIntegral = float(1.0 / cie::yIntegral());
    return sum * (invYIntegral / float(n));
}

}  // namespace iris
