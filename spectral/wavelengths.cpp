#include "spectral/wavelengths.h"

#include "core/error.h"

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

struct VisibleSample {
    float lambda, pdf;
};

/// Inverse-CDF sample of the visible pdf and its density. Invert F(λ) = (tanh(a(λ−c)) −
/// tanh(a(λmin−c))) / (a·norm) for t = tanh(a(λ−c)); then λ = c + atanh(t)/a with
/// atanh t = ½ ln((1 + t)/(1 − t)) (in double: more accurate than atanhf's log1pf, and cheaper), and,
/// because 1/cosh²x = 1 − tanh²x, the density is p = (1 − t²)/norm without another exp: it is
/// visibleWavelengthPdf at the unrounded λ (tests/test_wavelengths.cpp compares the two).
VisibleSample sampleVisibleAt(float u) {
    const float t = std::clamp(kVisTanhMin + u * kVisA * kVisNorm, -0.99999994f, 0.99999994f);
    const double td = t;
    constexpr double kHalfInvA = 0.5 / double(kVisA);
    const float lambda = float(double(kVisCenter) + kHalfInvA * std::log((1.0 + td) / (1.0 - td)));
    return {std::clamp(lambda, kLambdaMin, kLambdaMax), float((1.0 - td * td) * kVisInvNorm)};
}
}  // namespace

float sampleVisibleWavelength(float u) { return sampleVisibleAt(u).lambda; }

SampledWavelengths SampledWavelengths::sampleVisible(float u, int n) {
    if (n < 1 || n > kMaxWavelengths) fail("number of wavelengths must be in [1, ", kMaxWavelengths, "], got ", n);
    SampledWavelengths wl;
    wl.n_ = n;
    for (int i = 0; i < n; ++i) {
        float up = u + float(i) / n;
        if (up >= 1.0f) up -= 1.0f;
        const VisibleSample vs = sampleVisibleAt(up);
        wl.lambda_[i] = vs.lambda;
        wl.pdf_[i] = vs.pdf;
    }
    return wl;
}

SampledWavelengths SampledWavelengths::sampleUniform(float u, int n) {
    if (n < 1 || n > kMaxWavelengths) fail("number of wavelengths must be in [1, ", kMaxWavelengths, "], got ", n);
    SampledWavelengths wl;
    wl.n_ = n;
    const float range = kLambdaMax - kLambdaMin;
    for (int i = 0; i < n; ++i) {
        float up = u + float(i) / n;
        if (up >= 1.0f) up -= 1.0f;
        wl.lambda_[i] = kLambdaMin + up * range;
        wl.pdf_[i] = 1.0f / range;
    }
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

}  // namespace iris
