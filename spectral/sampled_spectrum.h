// A spectral quantity at the N wavelengths a path carries (N chosen per run, 1..kMaxWavelengths).
// In RGB mode N = 3 and the entries are the linear Rec.709 R, G, B channels.
#pragma once

#include <cassert>
#include <cmath>

#include "core/math.h"

namespace iris {

constexpr int kMaxWavelengths = 32;

class SampledSpectrum {
public:
    /// Element-wise arithmetic runs over the first n rounded up to a multiple of kLanes, in
    /// fixed-width groups that the compiler turns into SIMD instructions. The padding lanes
    /// (n..padded) are initialised by the constructors and never read by the queries below, so
    /// lanes 0..n−1 get exactly the values of a plain loop to n.
    static constexpr int kLanes = 4;
    static_assert(kMaxWavelengths % kLanes == 0);

    SampledSpectrum() = default;
    explicit SampledSpectrum(int n, float c = 0.0f) : n_(n) {
        assert(n >= 0 && n <= kMaxWavelengths);
        for (int i = 0; i < padded(); ++i) v_[i] = c;
    }

    int size() const { return n_; }
    float operator[](int i) const { return v_[i]; }
    float& operator[](int i) { return v_[i]; }

#define IRIS_SPECTRUM_OP(OP)                                                                  \
    SampledSpectrum& operator OP##=(const SampledSpectrum& o) {                               \
        assert(o.n_ == n_);                                                                   \
        forLanes(padded(), [&](int j) { v_[j] OP## = o.v_[j]; });                             \
        return *this;                                                                         \
    }                                                                                         \
    SampledSpectrum& operator OP##=(float s) {                                                \
        forLanes(padded(), [&](int j) { v_[j] OP## = s; });                                   \
        return *this;                                                                         \
    }                                                                                         \
    friend SampledSpectrum operator OP(const SampledSpectrum& a, const SampledSpectrum& b) {  \
        assert(a.n_ == b.n_);                                                                 \
        return fromLanes(a.n_, [&](int j) { return a.v_[j] OP b.v_[j]; });                    \
    }                                                                                         \
    friend SampledSpectrum operator OP(const SampledSpectrum& a, float s) {                   \
        return fromLanes(a.n_, [&](int j) { return a.v_[j] OP s; });                          \
    }
    IRIS_SPECTRUM_OP(+)
    IRIS_SPECTRUM_OP(-)
    IRIS_SPECTRUM_OP(*)
    IRIS_SPECTRUM_OP(/)
#undef IRIS_SPECTRUM_OP
    friend SampledSpectrum operator*(float s, const SampledSpectrum& a) {
        return fromLanes(a.n_, [&](int j) { return s * a.v_[j]; });
    }
    friend SampledSpectrum operator+(float s, const SampledSpectrum& a) {
        return fromLanes(a.n_, [&](int j) { return s + a.v_[j]; });
    }
    friend SampledSpectrum operator-(float s, const SampledSpectrum& a) {
        return fromLanes(a.n_, [&](int j) { return s - a.v_[j]; });
    }
    SampledSpectrum operator-() const {
        return fromLanes(n_, [&](int j) { return -v_[j]; });
    }

    /// Component-wise division that returns 0 where the divisor is 0 (for pdf ratios).
    friend SampledSpectrum safeDiv(const SampledSpectrum& a, const SampledSpectrum& b) {
        SampledSpectrum r(a.n_);
        for (int i = 0; i < a.n_; ++i) r.v_[i] = b.v_[i] != 0 ? a.v_[i] / b.v_[i] : 0.0f;
        return r;
    }

    bool isBlack() const {
        for (int i = 0; i < n_; ++i)
            if (v_[i] != 0) return false;
        return true;
    }
    bool hasNonFinite() const {
        for (int i = 0; i < n_; ++i)
            if (!std::isfinite(v_[i])) return true;
        return false;
    }
    bool hasNegative() const {
        for (int i = 0; i < n_; ++i)
            if (v_[i] < 0) return true;
        return false;
    }
    float maxValue() const {
        float m = n_ > 0 ? v_[0] : 0.0f;
        for (int i = 1; i < n_; ++i) m = std::max(m, v_[i]);
        return m;
    }
    float minValue() const {
        float m = n_ > 0 ? v_[0] : 0.0f;
        for (int i = 1; i < n_; ++i) m = std::min(m, v_[i]);
        return m;
    }
    float average() const {
        float s = 0;
        for (int i = 0; i < n_; ++i) s += v_[i];
        return n_ > 0 ? s / n_ : 0.0f;
    }

    template <typename F>
    friend SampledSpectrum map(const SampledSpectrum& a, F&& f) {
        SampledSpectrum r(a.n_);
        for (int i = 0; i < a.n_; ++i) r.v_[i] = f(a.v_[i]);
        return r;
    }
    friend SampledSpectrum sqrt(const SampledSpectrum& a) { return map(a, [](float x) { return safeSqrt(x); }); }
    friend SampledSpectrum exp(const SampledSpectrum& a) { return map(a, [](float x) { return std::exp(x); }); }
    friend SampledSpectrum clampZero(const SampledSpectrum& a) {
        return map(a, [](float x) { return std::max(0.0f, x); });
    }

    /// n rounded up to a multiple of kLanes: the lanes that forLanes / fromLanes visit.
    static constexpr int paddedSize(int n) { return (n + kLanes - 1) & ~(kLanes - 1); }
    int padded() const { return paddedSize(n_); }
    /// The lane storage (16-byte aligned, kMaxWavelengths long), for loops over all padded lanes
    /// outside this class (spectral/wavelengths.cpp, rgb_spectrum.cpp, xyz.cpp).
    float* lanes() { return v_; }
    const float* lanes() const { return v_; }

    /// f(j) for every lane j below `padded`, in fixed groups of kLanes (the SIMD-friendly loop).
    template <typename F>
    static void forLanes(int padded, F&& f) {
        for (int i = 0; i < padded; i += kLanes)
            for (int k = 0; k < kLanes; ++k) f(i + k);
    }
    /// A spectrum of n entries whose lane j (padding included) is f(j).
    template <typename F>
    static SampledSpectrum fromLanes(int n, F&& f) {
        SampledSpectrum r;
        r.n_ = n;
        forLanes(r.padded(), [&](int j) { r.v_[j] = f(j); });
        return r;
    }

private:
    int n_ = 0;
    alignas(16) float v_[kMaxWavelengths];
};

}  // namespace iris
