#include "spectral/xyz.h"

#include "spectral/lane_dispatch.h"

namespace iris {

namespace {
// w = L/pdf, 0 where pdf = 0, for `padded` lanes, four per operation (GCC leaves the plain loop
// scalar: the division's select is not if-converted); baseline and AVX2 builds (lane_dispatch.h).
// A lane whose pdf is 0 divides too, and its quotient is discarded by the select.
IRIS_LANES_INLINE void weightsBody(const float* l, const float* pdf, int padded, float* w) {
    for (int i = 0; i < padded; i += 4) {
        const lanes::Float4 p = lanes::load(pdf + i);
        lanes::store(w + i, lanes::select(p != 0.0f, lanes::load(l + i) / p, lanes::broadcast(0.0f)));
    }
}
IRIS_LANES_KERNEL(void, weights, weightsBody, (const float* l, const float* pdf, int padded, float* w), (l, pdf, padded, w))
}  // namespace

vec3 toXYZ(const SampledSpectrum& L, const SampledWavelengths& wl) {
    assert(!wl.isRGB());
    // Monte Carlo estimate of ∫ L(λ) cmf(λ) dλ with N correlated (hero) samples, then divided
    // by ∫ȳ dλ (docs/conventions.md, "Spectral and colour conventions").
    // Lane loops over the padded length (vectorised): the weights L/pdf, 0 where the pdf is 0
    // (terminated secondaries, and the padding lanes, whose pdf is 0 and whose L is not read);
    // then the CMF-weighted sum in wavelength order, so that the result is that of the plain loop
    // that skips zero-pdf entries (a skipped entry adds w·cmf = +0 here).
    const int n = wl.size();
    const int padded = SampledSpectrum::paddedSize(n);
    const float* pdf = wl.pdfs();
    const float* l = L.lanes();
    alignas(16) float w[kMaxWavelengths];
    weights(lanes::useAvx2For(padded), l, pdf, padded, w);
    const vec3 sum = cie::weightedXyzBarSum(wl.lambdas(), w, n);
    static const float invYIntegral = float(1.0 / cie::yIntegral());
    return sum * (invYIntegral / float(n));
}

}  // namespace iris
