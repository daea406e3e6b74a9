#include "render/splat_film.h"

#include <cmath>

#include "core/error.h"
#include "spectral/xyz.h"

namespace iris {

namespace {

/// ∫ f(x) dx over [−r, r] by the midpoint rule with 4096 cells (exact for the box filter; below
/// 1e-6 relative for the smooth ones).
float filterIntegral(const ReconstructionFilter& f) {
    constexpr int kCells = 4096;
    const double r = f.radius(), h = 2 * r / kCells;
    double sum = 0;
    for (int i = 0; i < kCells; ++i) sum += f.eval(float(-r + (i + 0.5) * h));
    return float(sum * h);
}

}  // namespace

void SplatFilm::AtomicSum::add(Film::FixedSum v) {
    const uint64_t vlo = uint64_t(v);
    int64_t vhi = int64_t(v >> 64);
    const uint64_t old = lo.fetch_add(vlo, std::memory_order_relaxed);
    if (old + vlo < old) ++vhi;  // the low word wrapped: carry
    if (vhi != 0) hi.fetch_add(vhi, std::memory_order_relaxed);
}

Film::FixedSum SplatFilm::AtomicSum::load() const {
    return Film::FixedSum(hi.load(std::memory_order_relaxed)) * (Film::FixedSum(1) << 64) +
           Film::FixedSum(lo.load(std::memory_order_relaxed));
}

SplatFilm::SplatFilm(int width, int height, const ReconstructionFilter& filter, bool rgbMode)
    : width_(width), height_(height), filter_(filter), norm_(filterIntegral(filter)),
      scale_(1.0f / (float(width) * float(height))), rgbMode_(rgbMode) {
    if (width <= 0 || height <= 0) fail("splat film size must be positive, got ", width, "x", height);
    if (!(norm_ != 0) || !std::isfinite(norm_)) fail("the reconstruction filter integrates to ", norm_, ": cannot splat with it");
    const uint64_t pixels = uint64_t(width) * uint64_t(height);
    MemoryAccount account;
    chargeMemory(pixels * 3 * sizeof(AtomicSum), strCat("splat buffer of ", width, "x", height, " pixels (light tracing)"));
    memory_ = account.take();
    sums_ = std::make_unique<AtomicSum[]>(3 * pixels);
}

vec3 SplatFilm::filmValue(const SampledSpectrum& L, const SampledWavelengths& wl) const {
    return rgbMode_ ? vec3(L[0], L[1], L[2]) : toXYZ(L, wl);
}

void SplatFilm::addChannels(size_t pixel, const vec3& value) {
    for (int c = 0; c < 3; ++c) {
        const Film::FixedSum v = Film::toFixed(value[c]);
        if (v != 0) sums_[3 * pixel + size_t(c)].add(v);
    }
}

void SplatFilm::add(int x, int y, const vec3& value) { addChannels(size_t(y) * size_t(width_) + size_t(x), value); }

void SplatFilm::splat(const vec2& filmPos, const SampledSpectrum& L, const SampledWavelengths& wl) {
    const vec3 value = filmValue(L, wl) * scale_;
    if (!isFinite(value) || L.hasNegative()) {
        invalid_.fetch_add(1, std::memory_order_relaxed);
        return;
    }
    if (value == vec3(0.0f)) return;
    const float r = filter_.radius();
    if (!(filmPos.x > -r - 1 && filmPos.x < float(width_) + r + 1 && filmPos.y > -r - 1 && filmPos.y < float(height_) + r + 1)) return;
    // Pixels whose centre (x + ½, y + ½) lies within the filter's radius of filmPos.
    const int x0 = std::max(0, int(std::floor(filmPos.x - 0.5f - r))), x1 = std::min(width_ - 1, int(std::ceil(filmPos.x - 0.5f + r)));
    const int y0 = std::max(0, int(std::floor(filmPos.y - 0.5f - r))), y1 = std::min(height_ - 1, int(std::ceil(filmPos.y - 0.5f + r)));
    const float invNorm2 = 1.0f / (norm_ * norm_);
    for (int y = y0; y <= y1; ++y) {
        const float dy = filmPos.y - (float(y) + 0.5f);
        if (!(std::abs(dy) < r)) continue;
        const float fy = filter_.eval(dy);
        for (int x = x0; x <= x1; ++x) {
            const float dx = filmPos.x - (float(x) + 0.5f);
            if (!(std::abs(dx) < r)) continue;
            const float w = filter_.eval(dx) * fy * invNorm2;
            if (w != 0.0f) add(x, y, value * w);
        }
    }
}

void SplatFilm::flushInto(Film& film) {
    if (film.width() != width_ || film.height() != height_) fail("splat film and film sizes differ");
    for (int y = 0; y < height_; ++y)
        for (int x = 0; x < width_; ++x) {
            const size_t i = size_t(y) * size_t(width_) + size_t(x);
            vec3 v;
            for (int c = 0; c < 3; ++c) v[c] = float(double(sums_[3 * i + size_t(c)].load()) * 0x1p-48);
            film.addSample(x, y, v);
        }
    clear();
}

void SplatFilm::clear() {
    const size_t n = 3 * size_t(width_) * size_t(height_);
    for (size_t i = 0; i < n; ++i) {
        sums_[i].lo.store(0, std::memory_order_relaxed);
        sums_[i].hi.store(0, std::memory_order_relaxed);
    }
}

}  // namespace iris
