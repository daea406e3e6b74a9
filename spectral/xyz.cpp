#include "spectral/xyz.h"

namespace iris {

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
    for (int i = 0; i < padded; ++i) w[i] = pdf[i] != 0.0f ? l[i] / pdf[i] : 0.0f;
    const vec3 sum = cie::weightedXyzBarSum(wl.lambdas(), w, n);
    static const float invYIntegral = float(1.0 / cie::yIntegral());
    return sum * (invYIntegral / float(n));
}

}  // namespace iris
