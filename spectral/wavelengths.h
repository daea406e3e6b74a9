// The wavelengths a path carries. Spectral mode: hero-wavelength sampling (Wilkie et al. 2014,
// "Hero Wavelength Spectral Sampling"): one wavelength from a visible-importance pdf and N−1
// stratified rotations of it in primary-sample space. RGB mode: three fixed channel wavelengths.
#pragma once

#include <array>
#include <bit>
#include <cstdint>

#include "core/math.h"
#include "spectral/sampled_spectrum.h"

namespace iris {

constexpr float kLambdaMin = 360.0f;  // nm, range of the CIE tables used
constexpr float kLambdaMax = 830.0f;

/// The wavelengths (nm) the R, G, B channels stand for by default: RGB mode's channel wavelengths
/// (render option --rgb-wavelengths), the thesis models' `wavelengths` default (thesis 000
/// Table 3.1) and the channel wavelengths of a per-channel index (spectral/ior.h). The one place
/// these numbers are written.
inline vec3 defaultChannelWavelengths() { return vec3(645.0f, 525.0f, 445.0f); }

/// Visible-importance wavelength pdf p(λ) ∝ 1/cosh²(0.0072(λ−538)) on [360, 830] nm
/// (the fit of pbrt-v4 §4.6.5, "SampleVisibleWavelengths"), normalised on that range.
float visibleWavelengthPdf(float lambda);
/// Inverse-CDF sample of visibleWavelengthPdf (closed form via atanh/tanh).
float sampleVisibleWavelength(float u);

/// ln x for a positive, finite, normal float x, in float, without a libm call and without branches
/// (so that a loop over lanes vectorises). Write x = m·2^k with m in [√½, √2) from the bit pattern
/// (k from the exponent field after shifting the bits by those of √½); then
/// ln m = 2 atanh(s) = 2(s + s³/3 + s⁵/5 + …), s = (m − 1)/(m + 1), |s| ≤ 3 − 2√2 = 0.1716
/// (Abramowitz & Stegun 4.1.27). Terms to s⁹/9: the first omitted term is below 2.3e-9 relative,
/// far under float rounding; m − 1 is exact (Sterbenz). ln x = k ln 2 + ln m, ln 2 split into a
/// float head and tail (Cody & Waite 1980) so that k ln 2 adds no error of its own.
[[gnu::always_inline]] inline float logPositive(float x) {
    const int32_t bits = std::bit_cast<int32_t>(x);
    constexpr int32_t kSqrtHalfBits = 0x3f3504f3;  // bit pattern of √½ = 0.70710677f
    const int32_t k = (bits - kSqrtHalfBits) >> 23;  // arithmetic shift (C++20)
    const float m = std::bit_cast<float>(bits - int32_t(uint32_t(k) << 23));
    const float s = (m - 1.0f) / (m + 1.0f);
    const float s2 = s * s;
    const float series = s2 * (1.0f / 3 + s2 * (1.0f / 5 + s2 * (1.0f / 7 + s2 * (1.0f / 9))));
    constexpr float kLn2Hi = 0.693145751953125f;  // ln 2 to 16 bits: k · kLn2Hi is exact
    constexpr float kLn2Lo = 1.42860682030941723212e-6f;
    const float kf = float(k);
    return kf * kLn2Hi + (kf * kLn2Lo + (2.0f * s + 2.0f * s * series));
}

class SampledWavelengths {
public:
    /// Spectral mode: u is the hero's primary sample; wavelength i uses (u + i/n) mod 1.
    static SampledWavelengths sampleVisible(float u, int n);
    /// Uniform sampling on [360, 830] (for tests and ablations of the wavelength pdf).
    static SampledWavelengths sampleUniform(float u, int n);
    /// Independent wavelengths (the ablation against the hero scheme of Wilkie et al. 2014):
    /// wavelength i from its own primary sample u[i], i < n, by the visible pdf or uniformly.
    /// Same marginal pdf per wavelength as the hero scheme, no stratification between them.
    static SampledWavelengths sampleIndependent(const float* u, int n, bool uniform);
    /// RGB mode: three channels at the given wavelengths (nm), pdf 1; values are linear Rec.709.
    static SampledWavelengths rgb(const vec3& channelLambdas);
    /// Spectral mode at n given wavelengths (nm, in [kLambdaMin, kLambdaMax]), pdf 1 each: for
    /// evaluating materials at chosen wavelengths (the Python module's BSDF queries).
    static SampledWavelengths fixed(const float* lambdas, int n);

    int size() const { return n_; }
    bool isRGB() const { return rgb_; }
    float lambda(int i) const { return lambda_[i]; }
    float pdf(int i) const { return pdf_[i]; }
    /// All lanes at once, for loops over SampledSpectrum::paddedSize(size()) entries (16-byte
    /// aligned). Padding lanes hold a wavelength inside [kLambdaMin, kLambdaMax] and pdf 0.
    const float* lambdas() const { return lambda_; }
    const float* pdfs() const { return pdf_; }
    /// cie::d65 at every lane's wavelength (padding included), computed once when the wavelengths
    /// are sampled: a path evaluates its illuminants several times at the same wavelengths.
    /// Spectral mode only (RGB mode never applies D65; there the lanes are 0).
    const float* d65Lanes() const { return d65_; }
    SampledSpectrum pdfSpectrum() const {
        SampledSpectrum p(n_);
        for (int i = 0; i < n_; ++i) p[i] = pdf_[i];
        return p;
    }

    /// Keep only the hero wavelength (after a dispersive refraction). The hero's pdf is divided
    /// by N so that the film's average over N wavelengths stays unbiased (pbrt-v4 §4.6.5).
    void terminateSecondary();
    bool secondaryTerminated() const;

private:
    int n_ = 0;
    bool rgb_ = false;
    alignas(16) float lambda_[kMaxWavelengths];
    alignas(16) float pdf_[kMaxWavelengths];
    alignas(16) float d65_[kMaxWavelengths];
};

/// The wavelength sets a scene parameter's constant spectrum is checked at when it is loaded: RGB
/// mode's three channels and kMaxWavelengths wavelengths evenly spaced over [kLambdaMin, kLambdaMax].
std::array<SampledWavelengths, 2> parameterCheckWavelengths();

}  // namespace iris
