// An optional per-wavelength image beside the film: for each pixel, the spectral radiance
// averaged over equal wavelength bins on [kLambdaMin, kLambdaMax] (the Python module's
// `spectral_bins`, docs/python.md). A path sample with wavelengths λ_i (pdf p_i, N of them) adds
// to bin b the estimator of the bin average (1/Δ) ∫_b L dλ:
//     (1/N) Σ_i 1[λ_i ∈ b] L(λ_i) / (p_i Δ)
// (the same Monte Carlo estimator as the film's XYZ, spectral/xyz.h, with the bin's indicator in
// place of the colour-matching functions); terminated secondary wavelengths (p_i = 0) are skipped.
// Each pixel is accumulated by one thread in sample order, like the Film. Spectral mode only.
#pragma once

#include <vector>

#include "spectral/sampled_spectrum.h"
#include "spectral/wavelengths.h"

namespace iris {

class SpectralFilm {
public:
    SpectralFilm(int width, int height, int bins);
    int bins() const { return bins_; }
    /// Centre wavelength (nm) of bin b.
    float binCenter(int b) const { return kLambdaMin + (float(b) + 0.5f) * binWidth_; }

    void addSample(int x, int y, const SampledSpectrum& L, const SampledWavelengths& wl);
    /// A sample whose estimate was invalid (NaN/Inf/negative; the film adds zero): counted only.
    void addZero(int x, int y) { count_[size_t(y) * width_ + x] += 1; }
    /// (height, width, bins) interleaved mean of each pixel's samples (0 where none).
    std::vector<float> meanImage() const;

private:
    int width_, height_, bins_;
    float binWidth_;
    std::vector<double> sum_;
    std::vector<uint32_t> count_;
};

}  // namespace iris
