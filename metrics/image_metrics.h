// Error metrics between a test image and a reference (definitions in docs/metrics.md), and
// per-pixel noise statistics over several independent renders for regression comparisons.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "core/io/image.h"

namespace iris {

/// ε in relMSE = mean (x − r)² / (r² + ε) (docs/metrics.md).
constexpr double kRelMSEEpsilon = 1e-2;
/// ε in SMAPE = mean |x − r| / (|x| + |r| + ε) (docs/metrics.md).
constexpr double kSmapeEpsilon = 1e-2;

struct ImageErrors {
    int width = 0, height = 0;
    int channels = 0;          // colour channels compared (1 or 3)
    size_t nonFinite = 0;      // values where test or ref is NaN/Inf, excluded from every metric
    double mse = 0;            // mean over pixels and channels of (x − r)²
    double relMse = 0;         // mean of (x − r)² / (r² + kRelMSEEpsilon)
    double smape = 0;          // mean of |x − r| / (|x| + |r| + kSmapeEpsilon), in [0, 1)
    double psnr = 0;           // 10 log10(1 / MSE of values clamped to [0,1]); +inf when identical
    double meanDeltaE00 = 0;   // mean CIEDE2000 over pixels (linear Rec.709 → CIELAB, D65, Y_white = 1)
    double p99DeltaE00 = 0;    // 99th percentile (nearest rank) of per-pixel ΔE00
    double maxDeltaE00 = 0;
};

/// The colour channels used by the metrics: R,G,B by name when present, else the first three
/// channels, else channel 0 alone (grey, replicated for ΔE). Throws if none.
std::vector<int> colourChannels(const Image& img);
/// The colour channels of both images (same count), after checking that their sizes agree;
/// throws iris::Error for a size or channel-count mismatch.
void matchedChannels(const Image& test, const Image& ref, std::vector<int>& ct, std::vector<int>& cr);

/// Compare `test` against `ref`. Throws iris::Error if the sizes or colour channel counts differ.
ImageErrors compareImages(const Image& test, const Image& ref);

/// Errors of one named channel (a colour channel or, for spectral images, one wavelength band).
struct ChannelErrors {
    std::string name;
    size_t count = 0;          // finite values compared
    double mse = 0, relMse = 0, smape = 0;
};
/// MSE, relMSE and SMAPE per channel, for every channel name that both images have (in the test
/// image's order), or for the given names (an error if one of the images lacks one). Made for
/// spectral images whose channels are wavelength bands; works on any channel names.
std::vector<ChannelErrors> channelErrors(const Image& test, const Image& ref, std::vector<std::string> names = {});

/// Per-pixel ΔE00 (one channel); pixels with a non-finite value get NaN.
Image deltaE00Map(const Image& test, const Image& ref);
/// test − ref on the colour channels (signed difference image).
Image differenceImage(const Image& test, const Image& ref);

/// Nearest-rank percentile (q in [0,100]) of `values` (reordered); NaN for an empty vector.
double percentile(std::vector<double> values, double q);

/// Per-pixel statistics over k ≥ 2 independent renders of the same scene (different seeds):
/// mean, unbiased sample variance of one render, and variance of the mean (= variance / k).
struct PixelStatistics {
    Image mean, variance, varianceOfMean;
    int count = 0;
};
PixelStatistics pixelStatistics(const std::vector<Image>& renders);

/// Regression check of `test` against a reference with known per-pixel noise: z_i = (x_i − r_i) /
/// sqrt(σ²_test,i + σ²_ref,i) over colour values with positive variance. If both images are unbiased
/// estimates of the same image, mean z² ≈ 1 and about 0.27% of |z| exceed 3.
struct NoiseComparison {
    size_t count = 0;             // values compared (positive variance, finite)
    double meanSquaredZ = 0;      // ≈ 1 when consistent
    double fractionAbove3 = 0;    // fraction with |z| > 3
};
NoiseComparison compareWithinNoise(const Image& test, const Image& testVariance, const Image& ref,
                                   const Image& refVariance);

}  // namespace iris
