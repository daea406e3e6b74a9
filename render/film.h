// The film: per-pixel sums of sample values (XYZ in spectral mode, linear Rec.709 RGB in RGB mode)
// with per-pixel sample counts. Pixel filtering is done by filter importance sampling
// (render/filters/rfilter.h: each sample lands in one pixel, offsets drawn from the filter, weight 1
// unless the filter has negative lobes), so the pixel value is the plain mean of its samples:
// renders of the same scene with different seeds can be merged by weighting with their sample
// counts, and sums are independent of threads.
//
// The sums are exact and order-independent: each sample value is rounded once to a fixed-point
// number (48 fraction bits, a 128-bit integer) and the integers are added, which is associative.
// So the films of disjoint sample ranges add up (Film::add) to bit for bit the film of the whole
// range rendered in one go (docs/cluster.md). The sums of squares (variance estimate only) stay in
// double precision.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iosfwd>
#include <string>
#include <vector>

#include "core/math.h"

namespace iris {

class Film {
public:
    /// Fixed-point sums: value · 2^kFractionBits rounded to the nearest integer.
    using FixedSum = __int128;
    static constexpr int kFractionBits = 48;
    /// Sample values are clamped to ±2^47 before rounding, so 2^32 samples cannot overflow 2^127.
    static constexpr double kMaxSampleValue = 0x1p47;
    static FixedSum toFixed(float v) {
        if (std::isnan(v)) return 0;  // the renderer drops invalid samples before; never UB here
        const double d = std::clamp(double(v), -kMaxSampleValue, kMaxSampleValue) * 0x1p48;  // exact
        const double r = std::nearbyint(d);  // round to nearest (even): the only rounding of a sample
        // Below 2^63 the integer fits an int64_t, whose conversion is one instruction; the 128-bit
        // conversion is a libgcc call (__fixdfti). Both are exact for an integer-valued double.
        if (std::abs(r) < 0x1p63) return FixedSum(int64_t(r));
        return FixedSum(r);
    }

    /// Bytes per pixel of the sums and counts (the loader charges them to the memory budget).
    static constexpr uint64_t kStateBytesPerPixel = 3 * sizeof(FixedSum) + 3 * sizeof(double) + sizeof(uint32_t);

    Film(int width, int height);
    int width() const { return width_; }
    int height() const { return height_; }

    void addSample(int x, int y, const vec3& value) {
        const size_t i = size_t(y) * width_ + x;
        const vec3 m = hasMomentSpace_ ? momentSpace_ * value : value;
        for (int c = 0; c < 3; ++c) {
            sum_[3 * i + c] += toFixed(value[c]);
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
    /// Interleaved 3-channel mean of the squared samples (the second moment; 0 where no samples).
    std::vector<float> secondMomentImage() const;
    /// Interleaved 3-channel estimated variance of each pixel's mean: s²/n with the unbiased
    /// sample variance s² (0 where fewer than 2 samples), in the moment space (setMomentSpace).
    std::vector<float> varianceOfMeanImage() const;

    /// Add another film's samples (same size): exact for the sums and counts, so adding the films
    /// of disjoint sample ranges gives the film of their union whatever the order.
    void add(const Film& other);

    /// Exact binary state (sums and counts) for checkpoints. Throws iris::Error naming the file.
    /// `header` is text; its first line identifies the scene and settings (Renderer::settingsKey),
    /// further lines describe the state (the sample range, Renderer::stateHeader).
    void save(const std::string& path, const std::string& header) const;
    /// Load a checkpoint written by save(); the first line of its header must equal `key` exactly.
    /// A truncated, corrupted (CRC-32) or foreign file throws iris::Error and leaves the film as it was.
    void load(const std::string& path, const std::string& key);
    /// Read a state file of any size; its whole header goes to *header.
    static Film read(const std::string& path, std::string* header);

private:
    void takeBody(const std::string& in, size_t pos);  // sums, squares, counts from a checked file
    int width_, height_;
    std::vector<FixedSum> sum_;
    std::vector<double> sumSq_;
    std::vector<uint32_t> count_;
    mat3 momentSpace_{1.0f};
    bool hasMomentSpace_ = false;
};

}  // namespace iris
