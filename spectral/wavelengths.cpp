#include "spectral/wavelengths.h"

#include "core/error.h"
#include "spectral/cie.h"
#include "spectral/lane_dispatch.h"

namespace iris {

namespace {
constexpr float kVisA = 0.0072f;     // 1/nm
constexpr float kVisCenter = 538.0f;  // nm
// ∫ 1/cosh²(a(λ−c)) dλ = tanh(a(λ−c))/a.
float visibleCdfRaw(float lambda) { return std::tanh(kVisA * (lambda - kVisCenter)) / kVisA; }
const float kVisNorm = visibleCdfRaw(kLambdaMax) - visibleCdfRaw(kLambdaMin);
}  // namespace

float visibleWavelengthPdf(float lambda) {
    if (lambda < kLambdaMin || lambda > kLambdaMax) return 0.0f;
    // 1/cosh²(x) = 4e^{−2|x|} / (1 + e^{−2|x|})² (cosh x = e^{|x|}(1 + e^{−2|x|})/2): one exp
    // instead of cosh's exp/expm1 pair; equal to the cosh form up to float rounding.
    const float e = std::exp(-2.0f * std::abs(kVisA * (lambda - kVisCenter)));
    return 4.0f * e / (kVisNorm * sqr(1.0f + e));
}

namespace {
const float kVisTanhMin = std::tanh(kVisA * (kLambdaMin - kVisCenter));
const double kVisInvNorm = 1.0 / double(kVisNorm);

/// Inverse-CDF sample of the visible pdf and its density. Invert F(λ) = (tanh(a(λ−c)) −
/// tanh(a(λmin−c))) / (a·norm) for t = tanh(a(λ−c)); then λ = c + atanh(t)/a with
/// atanh t = ½ ln((1 + t)/(1 − t)), the logarithm by logPositive (float; λ differs from the
/// double-precision libm form by about an ulp of λ, tests/spectral/test_wavelengths.cpp), and, because
/// 1/cosh²x = 1 − tanh²x, the density is p = (1 − t²)/norm without another exp: it is
/// visibleWavelengthPdf at the unrounded λ (tests/spectral/test_wavelengths.cpp compares the two).
/// Inline and branch-free: sampleVisible runs it over all lanes in one vectorised loop.
struct VisibleSample {
    float lambda, pdf;
};
IRIS_LANES_INLINE VisibleSample sampleVisibleAt(float u) {
    const float t = std::clamp(kVisTanhMin + u * kVisA * kVisNorm, -0.99999994f, 0.99999994f);
    constexpr float kHalfInvA = float(0.5 / double(kVisA));
    const float lambda = kVisCenter + kHalfInvA * logPositive((1.0f + t) / (1.0f - t));
    const double td = t;
    return {std::clamp(lambda, kLambdaMin, kLambdaMax), float((1.0 - td * td) * kVisInvNorm)};
}

/// Primary sample of hero rotation i of n: (u + i/n) mod 1 (for u in [0, 1)), branch-free: the
/// integer part of u + i/n is 0 or 1 for the real lanes, and up − 1 is exact for up in [1, 2).
IRIS_LANES_INLINE float rotatedSample(float u, int i, int n) {
    const float up = u + float(i) / float(n);
    return up - float(int(up));
}

/// Every lane of sampleVisible, in the baseline and the AVX2 build (spectral/lane_dispatch.h).
IRIS_LANES_INLINE void sampleVisibleLanesBody(float u, int n, float* lambda, float* pdf) {
    const int padded = SampledSpectrum::paddedSize(n);
    for (int i = 0; i < padded; ++i) {
        const VisibleSample vs = sampleVisibleAt(rotatedSample(u, i, n));
        lambda[i] = vs.lambda;
        pdf[i] = vs.pdf;
    }
}
IRIS_LANES_KERNEL(void, sampleVisibleLanes, sampleVisibleLanesBody, (float u, int n, float* lambda, float* pdf),
                  (u, n, lambda, pdf))

/// Padding lanes: a valid wavelength, pdf 0 (SampledWavelengths::lambdas()).
void clearPadding(int n, float* lambda, float* pdf) {
    for (int i = n; i < SampledSpectrum::paddedSize(n); ++i) {
        lambda[i] = kLambdaMin;
        pdf[i] = 0.0f;
    }
}
}  // namespace

float sampleVisibleWavelength(float u) { return sampleVisibleAt(u).lambda; }

SampledWavelengths SampledWavelengths::sampleVisible(float u, int n) {
    if (n < 1 || n > kMaxWavelengths) fail("number of wavelengths must be in [1, ", kMaxWavelengths, "], got ", n);
    SampledWavelengths wl;
    wl.n_ = n;
    sampleVisibleLanes(lanes::useAvx2For(SampledSpectrum::paddedSize(n)), u, n, wl.lambda_, wl.pdf_);
    clearPadding(n, wl.lambda_, wl.pdf_);
    const int padded = SampledSpectrum::paddedSize(n);
    cie::d65Lanes(wl.lambda_, padded, wl.d65_);
    return wl;
}

SampledWavelengths SampledWavelengths::sampleUniform(float u, int n) {
    if (n < 1 || n > kMaxWavelengths) fail("number of wavelengths must be in [1, ", kMaxWavelengths, "], got ", n);
    SampledWavelengths wl;
    wl.n_ = n;
    const float range = kLambdaMax - kLambdaMin;
    const int padded = SampledSpectrum::paddedSize(n);
    for (int i = 0; i < padded; ++i) {
        wl.lambda_[i] = kLambdaMin + rotatedSample(u, i, n) * range;
        wl.pdf_[i] = 1.0f / range;
    }
    clearPadding(n, wl.lambda_, wl.pdf_);
    cie::d65Lanes(wl.lambda_, padded, wl.d65_);
    return wl;
}

SampledWavelengths SampledWavelengths::sampleIndependent(const float* u, int n, bool uniform) {
    if (n < 1 || n > kMaxWavelengths) fail("number of wavelengths must be in [1, ", kMaxWavelengths, "], got ", n);
    SampledWavelengths wl;
    wl.n_ = n;
    const float range = kLambdaMax - kLambdaMin;
    for (int i = 0; i < n; ++i) {
        const VisibleSample vs = uniform ? VisibleSample{kLambdaMin + u[i] * range, 1.0f / range} : sampleVisibleAt(u[i]);
        wl.lambda_[i] = std::min(vs.lambda, kLambdaMax);
        wl.pdf_[i] = vs.pdf;
    }
    clearPadding(n, wl.lambda_, wl.pdf_);
    cie::d65Lanes(wl.lambda_, SampledSpectrum::paddedSize(n), wl.d65_);
    return wl;
}

SampledWavelengths SampledWavelengths::rgb(const vec3& channelLambdas) {
    SampledWavelengths wl;
    wl.n_ = 3;
    wl.rgb_ = true;
    for (int i = 0; i < 3; ++i) {
        wl.lambda_[i] = channelLambdas[i];
        wl.pdf_[i] = 1.0f;
    }
    clearPadding(3, wl.lambda_, wl.pdf_);
    for (int i = 0; i < SampledSpectrum::paddedSize(3); ++i) wl.d65_[i] = 0.0f;
    return wl;
}

SampledWavelengths SampledWavelengths::fixed(const float* lambdas, int n) {
    if (n < 1 || n > kMaxWavelengths) fail("number of wavelengths must be in [1, ", kMaxWavelengths, "], got ", n);
    SampledWavelengths wl;
    wl.n_ = n;
    for (int i = 0; i < n; ++i) {
        if (!(lambdas[i] >= kLambdaMin && lambdas[i] <= kLambdaMax))
            fail("wavelength ", lambdas[i], " nm is outside [", kLambdaMin, ", ", kLambdaMax, "] nm");
        wl.lambda_[i] = lambdas[i];
        wl.pdf_[i] = 1.0f;
    }
    clearPadding(n, wl.lambda_, wl.pdf_);
    cie::d65Lanes(wl.lambda_, SampledSpectrum::paddedSize(n), wl.d65_);
    return wl;
}

void SampledWavelengths::terminateSecondary() {
    if (rgb_ || secondaryTerminated()) return;
    for (int i = 1; i < n_; ++i) pdf_[i] = 0.0f;
    pdf_[0] /= float(n_);
}

bool SampledWavelengths::secondaryTerminated() const {
    for (int i = 1; i < n_; ++i)
        if (pdf_[i] != 0.0f) return false;
    return n_ > 1;
}

std::array<SampledWavelengths, 2> parameterCheckWavelengths() {
    float lambdas[kMaxWavelengths];
    for (int k = 0; k < kMaxWavelengths; ++k) lambdas[k] = kLambdaMin + (kLambdaMax - kLambdaMin) * k / (kMaxWavelengths - 1);
    return {SampledWavelengths::rgb(defaultChannelWavelengths()), SampledWavelengths::fixed(lambdas, kMaxWavelengths)};
}

}  // namespace iris
