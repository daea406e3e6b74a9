// The per-wavelength lane type: four floats or four doubles operated on element-wise (GCC/Clang
// vector extensions), and the few operations the lane kernels need beyond the built-in + − × ÷
// and comparisons: load/store, broadcast, select, min/max/clamp (std::min/max/clamp semantics),
// sqrt, abs, copysign, integer conversion and the bit mask of a comparison. Every operation is an
// IEEE element-wise operation (correctly rounded; no FMA contraction: no build enables FMA), so
// lane k of a lane computation is bit for bit the scalar computation of the same operations in the
// same order (tests/spectral/test_lanes.cpp checks each operation against its scalar form, in both
// builds of spectral/lane_dispatch.h). The baseline x86-64 build lowers Float4 to one SSE register
// and Double4 to two; the AVX2 build Double4 to one. The only target-specific code (the float
// square root) is in this header; no other file uses intrinsics.
#pragma once

#include <cstdint>
#include <cstring>

// Double4 is passed and returned in registers only between always-inline functions; GCC's note that
// a 32-byte vector's ABI differs with and without AVX concerns calls that never happen.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"

namespace iris::lanes {

#define IRIS_LANES_INLINE [[gnu::always_inline]] inline

typedef float Float4 __attribute__((vector_size(16)));
typedef double Double4 __attribute__((vector_size(32)));

/// The mask type of a comparison of two V (each lane all ones: true, 0: false).
template <typename V>
using Mask = decltype(V{} < V{});
using Int4 = Mask<Float4>;    // 4 × int32: Float4 comparisons, integer lanes
using Long4 = Mask<Double4>;  // 4 × int64: Double4 comparisons

IRIS_LANES_INLINE Float4 load(const float* p) {
    Float4 v;
    std::memcpy(&v, p, sizeof v);  // unaligned load
    return v;
}
IRIS_LANES_INLINE Double4 load(const double* p) {
    Double4 v;
    std::memcpy(&v, p, sizeof v);
    return v;
}
IRIS_LANES_INLINE void store(float* p, Float4 v) { std::memcpy(p, &v, sizeof v); }
IRIS_LANES_INLINE void store(double* p, Double4 v) { std::memcpy(p, &v, sizeof v); }
IRIS_LANES_INLINE void store(int32_t* p, Int4 v) { std::memcpy(p, &v, sizeof v); }

/// x in every lane.
IRIS_LANES_INLINE Float4 broadcast(float x) { return Float4{x, x, x, x}; }
IRIS_LANES_INLINE Double4 broadcast(double x) { return Double4{x, x, x, x}; }
IRIS_LANES_INLINE Int4 broadcast(int32_t x) { return Int4{x, x, x, x}; }

/// Per lane m ? a : b.
template <typename V>
IRIS_LANES_INLINE V select(Mask<V> m, V a, V b) {
    return m ? a : b;
}
/// std::min(a, b) per lane (b < a ? b : a: a NaN b gives a).
template <typename V>
IRIS_LANES_INLINE V min(V a, V b) {
    return b < a ? b : a;
}
/// std::max(a, b) per lane (a < b ? b : a).
template <typename V>
IRIS_LANES_INLINE V max(V a, V b) {
    return a < b ? b : a;
}
/// std::clamp(v, lo, hi) per lane (v < lo ? lo : hi < v ? hi : v).
template <typename V>
IRIS_LANES_INLINE V clamp(V v, V lo, V hi) {
    return v < lo ? lo : (hi < v ? hi : v);
}

/// Correctly rounded square root per lane (= std::sqrt).
IRIS_LANES_INLINE Float4 sqrt(Float4 a) {
#if defined(__SSE__)
    return __builtin_ia32_sqrtps(a);  // one sqrtps, whatever the file's errno flags
#else
    Float4 r;
    for (int i = 0; i < 4; ++i) r[i] = __builtin_sqrtf(a[i]);
    return r;
#endif
}
IRIS_LANES_INLINE Double4 sqrt(Double4 a) {
    // sqrtpd (two in the baseline build, one in AVX2) where the file has -fno-math-errno; four
    // scalar square roots otherwise (the same values).
    Double4 r;
    for (int i = 0; i < 4; ++i) r[i] = __builtin_sqrt(a[i]);
    return r;
}

/// |a| per lane (clears the sign bit, as std::abs / std::fabs).
IRIS_LANES_INLINE Double4 abs(Double4 a) { return (Double4)((Long4)a & 0x7fffffffffffffffLL); }
IRIS_LANES_INLINE Float4 abs(Float4 a) { return (Float4)((Int4)a & 0x7fffffff); }
/// std::copysign(mag, sgn) per lane.
IRIS_LANES_INLINE Double4 copysign(Double4 mag, Double4 sgn) {
    return (Double4)(((Long4)mag & 0x7fffffffffffffffLL) | ((Long4)sgn & (long long)0x8000000000000000ULL));
}
IRIS_LANES_INLINE Float4 copysign(Float4 mag, Float4 sgn) {
    return (Float4)(((Int4)mag & 0x7fffffff) | ((Int4)sgn & int32_t(0x80000000u)));
}

/// int(x) per lane (truncation toward zero, as the scalar conversion) and back.
IRIS_LANES_INLINE Int4 toInt(Float4 x) { return __builtin_convertvector(x, Int4); }
IRIS_LANES_INLINE Float4 toFloat(Int4 i) { return __builtin_convertvector(i, Float4); }
/// float(x) per lane (rounded to nearest, as the scalar conversion) and double(x) (exact).
IRIS_LANES_INLINE Float4 toFloat(Double4 x) { return __builtin_convertvector(x, Float4); }
IRIS_LANES_INLINE Double4 toDouble(Float4 x) { return __builtin_convertvector(x, Double4); }

/// Bit k set where lane k of the mask is true.
IRIS_LANES_INLINE int bits(Long4 m) { return int(m[0] & 1) | int(m[1] & 2) | int(m[2] & 4) | int(m[3] & 8); }
IRIS_LANES_INLINE int bits(Int4 m) { return int(m[0] & 1) | int(m[1] & 2) | int(m[2] & 4) | int(m[3] & 8); }

}  // namespace iris::lanes

#pragma GCC diagnostic pop
