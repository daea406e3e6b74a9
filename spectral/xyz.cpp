#include "spectral/xyz.h"

namespace iris {

vec3 toXYZ(const SampledSpectrum& L, const SampledWavelengths& wl) {
    assert(!wl.isRGB());
    // Monte Carlo estimate of ∫ L(λ) cmf(λ) dλ with N correlated (hero) samples, then divided
    // by ∫ȳ dλ (docs/conventions.md, "Spectral and colour conventions").
    // Lane loops over the padded length (vectorised): the weights L/pdf, 0 where the pdf is 0
    // (terminated secondaries, and the padding lanes, whose pdf is 0 and whose L is not read);
    // then the CMF lookups for all lanes; then the sums in wavelength order, so that the result
    // is the one of the plain loop that skips zero-pdf entries (a skipped entry adds +0 here).
    const int n = wl.size();
    const int padded = SampledSpectrum::paddedSize(n);
    const float* pdf = wl.pdfs();
    const float* l = L.lanes();
    alignas(16) float w[kMaxWavelengths], xb[kMaxWavelengths], yb[kMaxWavelengths], zb[kMaxWavelengths];
    for (int i = 0; i < padded; ++i) w[i] = pdf[i] != 0.0f ? l[i] / pdf[i] : 0.0f;
    cie::xyzBarLanes(wl.lambdas(), padded, xb, yb, zb);
    float sx = 0.0f, sy = 0.0f, sz = 0.0f;
    for (int i = 0; i < n; ++i) {
        sx += w[i] * xb[i];
        sy += w[i] * yb[i];
        sz += w[i] * zb[i];
    }
    static const float invYIntegral = float(1.0 / cie::yIntegral());
    return vec3(sx, sy, sz) * (invYIntegral / float(n));
}

}  // namespace iris
