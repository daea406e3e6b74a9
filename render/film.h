// The film: per-pixel sums of sample values (XYZ in spectral mode, linear Rec.709 RGB in RGB mode)
// in double precision, with per-pixel sample counts. Pixel filtering is done by filter importance
// sampling (render/filters/rfilter.h: each sample lands in one pixel, offsets drawn from the
// filter, weight 1 unless the filter has negative lobes), so the pixel value is the plain mean of
// its samples: renders of the same scene with different seeds can
// be merged exactly by weighting with their sample counts, and sums are independent of threads.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/math.h"

namespace iris {

class Film {
public:
    Film(int width, int height);
    int width() const { return width_; }
    int height() const { return height_; }

    void addSample(int x, int y, const vec3& value) {
        const size_t i = size_t(y) * width_ + x;
        for (int c = 0; c < 3; ++c) {
            sum_[3 * i + c] += value[c];
            sumSq_[3 * i + c] += double(value[c]) * value[c];
        }
        count_[i] += 1;
    }
    /// Mean of the samples at a pixel (0 if none).
    vec3 pixel(int x, int y) const;
    uint32_t sampleCount(int x, int y) const { return count_[size_t(y) * width_ + x]; }
    uint64_t totalSamples() const;
    uint32_t minSampleCount() const;

    /// Interleaved 3-channel mean image.
    std::vector<float> meanImage() const;
    /// Interleaved 3-channel mean of the squared samples (the second moment; 0 where no samples).
    std::vector<float> secondMomentImage() const;
    /// Interleaved 3-channel estimated variance of each pixel's mean: s²/n with the unbiased
    /// sample variance s² (0 where fewer than 2 samples).
    std::vector<float> varianceOfMeanImage() const;

    /// Exact binary state (sums and counts) for checkpoints. Throws iris::Error naming the file.
    void save(const std::string& path, const std::string& header) const;
    /// Load a checkpoint written by save(); `header` must match exactly (scene, settings).
    void load(const std::string& path, const std::string& header);

private:
    int width_, height_;
    std::vector<double> sum_, sumSq_;
    std::vector<uint32_t> count_;
};

}  // namespace iris
