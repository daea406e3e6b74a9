// The film: per-pixel sums of sample values (XYZ in spectral mode, linear Rec.709 RGB in RGB mode)
// in double precision, with per-pixel sample counts. Pixel filtering is done by filter importance
// sampling (each sample lands in one pixel with weight 1, offsets drawn from the filter), so the
// pixel value is the plain mean of its samples: renders of the same scene with different seeds can
// be merged exactly by weighting with their sample counts, and sums are independent of threads.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/math.h"
#include "render/scene_description.h"

namespace iris {

/// Samples a film-plane offset (pixels) from the pixel filter: box of half-width r, or a Gaussian
/// of standard deviation σ truncated at 3σ (Mitsuba's default gaussian: σ = 0.5 px). The Gaussian
/// is sampled per axis through a tabulated inverse CDF (built once, 1025 entries, linear
/// interpolation; the table is exact at its nodes to float precision).
class PixelFilter {
public:
    explicit PixelFilter(const CameraDescription& d);
    vec2 sample(const vec2& u) const;

private:
    float sample1D(float u) const;
    CameraDescription::Filter type_;
    float radius_, stddev_;
    std::vector<float> inverseCdf_;
};

class Film {
public:
    Film(int width, int height);
    int width() const { return width_; }
    int height() const { return height_; }

    void addSample(int x, int y, const vec3& value) {
        const size_t i = size_t(y) * width_ + x;
        const vec3 m = hasMomentSpace_ ? momentSpace_ * value : value;
        for (int c = 0; c < 3; ++c) {
            sum_[3 * i + c] += value[c];
            sumSq_[3 * i + c] += double(m[c]) * m[c];
        }
        count_[i] += 1;
    }
    /// Accumulate the second moments of M·value instead of value (call before adding samples), so
    /// that varianceOfMeanImage() is the per-channel variance in another linear colour space (e.g.
    /// CIE XYZ for an RGB-mode film: a per-channel RGB variance cannot be converted afterwards
    /// without the cross-channel covariances).
    void setMomentSpace(const mat3& m) {
        momentSpace_ = m;
        hasMomentSpace_ = true;
    }
    /// Mean of the samples at a pixel (0 if none).
    vec3 pixel(int x, int y) const;
    uint32_t sampleCount(int x, int y) const { return count_[size_t(y) * width_ + x]; }
    uint64_t totalSamples() const;
    uint32_t minSampleCount() const;

    /// Interleaved 3-channel mean image.
    std::vector<float> meanImage() const;
    /// Interleaved 3-channel estimated variance of each pixel's mean: s²/n with the unbiased
    /// sample variance s² (0 where fewer than 2 samples), in the moment space (setMomentSpace).
    std::vector<float> varianceOfMeanImage() const;

    /// Exact binary state (sums and counts) for checkpoints. Throws iris::Error naming the file.
    void save(const std::string& path, const std::string& header) const;
    /// Load a checkpoint written by save(); `header` must match exactly (scene, settings).
    void load(const std::string& path, const std::string& header);

private:
    int width_, height_;
    std::vector<double> sum_, sumSq_;
    std::vector<uint32_t> count_;
    mat3 momentSpace_{1.0f};
    bool hasMomentSpace_ = false;
};

}  // namespace iris
