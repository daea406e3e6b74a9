// The spectral film of `render --spectral-output` (issue 15): per pixel, the mean spectral
// radiance in each wavelength bin (spectral/spectral_bins.h), written in the OpenEXR spectral
// layout of Fichet et al. 2021 (core/io/spectral_layout.h). A path sample at wavelengths λ_i
// (i < N) with pdf p(λ_i) adds L(λ_i) / (N p(λ_i) Δ_b) to the bin b holding λ_i: its expectation
// is (1/Δ_b) ∫_b L(λ) dλ, since E[(1/N) Σ_i f(λ_i)/p(λ_i)] = ∫ f dλ for each λ_i distributed as p
// (the hero scheme of Wilkie et al. 2014 gives every λ_i that marginal pdf). Sums in double with
// per-pixel sample counts, like render/film.h; the pixel value is the plain mean.
#pragma once

#include <cstdint>
#include <vector>

#include "core/io/image.h"
#include "spectral/sampled_spectrum.h"
#include "spectral/spectral_bins.h"
#include "spectral/wavelengths.h"

namespace iris {

class SpectralFilm {
public:
    /// Throws iris::Error for a non-positive size or a film of more than 2^28 bin values.
    SpectralFilm(int width, int height, const SpectralBins& bins);
    int width() const { return width_; }
    int height() const { return height_; }
    const SpectralBins& bins() const { return bins_; }

    /// One sample of a pixel (spectral mode only: RGB-mode wavelengths are not a density).
    void addSample(int x, int y, const SampledSpectrum& L, const SampledWavelengths& wl);
    /// A sample whose estimate was discarded (non-finite or negative): counted, adds nothing, as
    /// the colour film counts it with value 0.
    void addZeroSample(int x, int y) { ++count_[size_t(y) * size_t(width_) + size_t(x)]; }
    uint32_t sampleCount(int x, int y) const { return count_[size_t(y) * size_t(width_) + size_t(x)]; }

    /// Mean radiance per bin: one channel per bin named by spectralChannelName(centre).
    Image image() const;

private:
    int width_, height_;
    SpectralBins bins_;
    std::vector<double> sum_;  // (y * width + x) * bins + b
    std::vector<uint32_t> count_;
};

}  // namespace iris
