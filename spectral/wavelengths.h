// The wavelengths a path carries. Spectral mode: hero-wavelength sampling (Wilkie et al. 2014,
// "Hero Wavelength Spectral Sampling"): one wavelength from a visible-importance pdf and N−1
// stratified rotations of it in primary-sample space. RGB mode: three fixed channel wavelengths.
#pragma once

#include "core/math.h"
#include "spectral/sampled_spectrum.h"

namespace iris {

constexpr float kLambdaMin = 360.0f;  // nm, range of the CIE tables used
constexpr float kLambdaMax = 830.0f;

/// Visible-importance wavelength pdf p(λ) ∝ 1/cosh²(0.0072(λ−538)) on [360, 830] nm
/// (the fit of pbrt-v4 §4.6.5, "SampleVisibleWavelengths"), normalised on that range.
float visibleWavelengthPdf(float lambda);
/// Inverse-CDF sample of visibleWavelengthPdf (closed form via atanh/tanh).
float sampleVisibleWavelength(float u);

class SampledWavelengths {
public:
    /// Spectral mode: u is the hero's primary sample; wavelength i uses (u + i/n) mod 1.
    static SampledWavelengths sampleVisible(float u, int n);
    /// Uniform sampling on [360, 830] (for tests and ablations of the wavelength pdf).
    static SampledWavelengths sampleUniform(float u, int n);
    /// RGB mode: three channels at the given wavelengths (nm), pdf 1; values are linear Rec.709.
    static SampledWavelengths rgb(const vec3& channelLambdas);

    int size() const { return n_; }
    bool isRGB() const { return rgb_; }
    float lambda(int i) const { return lambda_[i]; }
    float pdf(int i) const { return pdf_[i]; }
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
    float lambda_[kMaxWavelengths];
    float pdf_[kMaxWavelengths];
};

}  // namespace iris
