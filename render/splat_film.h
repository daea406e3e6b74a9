// The splats of one pass of a light-tracing render (ptracer, bdpt). A light path reaches the film
// anywhere, so its contributions ("splats", pbrt-v4 §5.4.4 Film::AddSplat) land in pixels other
// threads are rendering. They are added here, as the film adds its samples, in fixed point
// (render/film.h: 48 fraction bits, each value rounded once) but through atomic 64-bit additions
// with a carry into the upper word: integer addition is associative and commutative, so the sums
// are the same bits whatever the threads and their order. At the end of a complete pass every
// pixel's sum becomes one sample of the film (flushInto): the pixel's value is then the mean over
// passes of "everything that reached the pixel in that pass", whose variance the film's second
// moments estimate as for any other sample, and checkpoints, resume and split renders work on the
// film as they do for `path` (docs/rendering.md). A pass that is interrupted is dropped: its splats
// cover the whole image and would be partial.
//
// A splat at film position p adds value · h(p − c) to the pixel of centre c, with h the
// reconstruction filter normalised to integrate to 1 (the filter the camera samples draw their
// offsets from, render/filters/rfilter.h: the expectations agree), times `scale` = 1 / (the number
// of light paths of a pass, one per pixel: width × height), as Mitsuba 3's AdjointIntegrator
// sample_scale.
#pragma once

#include <atomic>
#include <memory>
#include <vector>

#include "core/math.h"
#include "core/memory_budget.h"
#include "render/film.h"
#include "render/filters/rfilter.h"
#include "spectral/sampled_spectrum.h"
#include "spectral/wavelengths.h"

namespace iris {

class SplatFilm {
public:
    /// `rgbMode`: values are the three channels as linear Rec.709; else spectra become CIE XYZ (as
    /// the renderer converts camera samples). Charges its buffer to the memory budget.
    SplatFilm(int width, int height, const ReconstructionFilter& filter, bool rgbMode);
    int width() const { return width_; }
    int height() const { return height_; }
    /// The film positions that reach a pixel: the image and a margin of the filter's radius.
    float margin() const { return filter_.radius(); }

    /// A light path's contribution arriving at film position filmPos (pixels), spread by the filter
    /// and scaled by 1/(width × height). Thread-safe. Invalid values (NaN, ±Inf, negative) are
    /// counted and dropped.
    void splat(const vec2& filmPos, const SampledSpectrum& L, const SampledWavelengths& wl);
    /// A value of pixel (x, y) itself, in the film's space, unscaled (a camera sample's own
    /// estimate, its filter weight applied). Thread-safe.
    void add(int x, int y, const vec3& value);
    /// The film's space of a path's value: XYZ or the RGB channels.
    vec3 filmValue(const SampledSpectrum& L, const SampledWavelengths& wl) const;

    /// Adds every pixel's sum as one sample of `film` (same size) and clears the sums.
    void flushInto(Film& film);
    /// Forgets the sums (an interrupted pass).
    void clear();
    /// Splats dropped as invalid so far.
    uint64_t invalidSplats() const { return invalid_.load(std::memory_order_relaxed); }

private:
    /// A 128-bit fixed-point sum from two 64-bit atomics: the low word's wrap-arounds are carried
    /// into the high word, so the pair holds the exact sum of every value added once all additions
    /// are done, in any order.
    struct AtomicSum {
        std::atomic<uint64_t> lo{0};
        std::atomic<int64_t> hi{0};
        void add(Film::FixedSum v);
        Film::FixedSum load() const;
    };
    void addChannels(size_t pixel, const vec3& value);

    int width_, height_;
    const ReconstructionFilter& filter_;
    float norm_;   // ∫ f(x) dx over the filter's support: h(x, y) = f(x) f(y) / norm²
    float scale_;  // 1 / (width × height)
    bool rgbMode_;
    std::unique_ptr<AtomicSum[]> sums_;  // 3 per pixel
    std::atomic<uint64_t> invalid_{0};
    std::shared_ptr<const MemoryReservation> memory_;
};

}  // namespace iris
