// Run-time choice between two builds of a per-wavelength lane loop (spectral/lanes.h): the
// baseline x86-64 (SSE2, 4 floats per instruction) and AVX2 (8 floats per instruction, no FMA: the
// floating-point operations and their order are the same, so the two builds give bit-identical
// results; tests/spectral/test_lanes.cpp and test_spectral_lanes.cpp run both and compare). The
// binary stays runnable on any x86-64 (no -march flag): the AVX2 build is only called when the CPU
// reports AVX2. A kernel is written once as an always-inline body and instantiated by one macro:
//
//   IRIS_LANES_INLINE void scaleBody(const float* x, int n, float* y) { for (...) ... }
//   IRIS_LANES_KERNEL(void, scale, scaleBody, (const float* x, int n, float* y), (x, n, y))
//   ... scale(lanes::useAvx2For(n), x, n, y);
#pragma once

#include <atomic>

#include "spectral/lanes.h"

namespace iris::lanes {

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define IRIS_LANES_HAVE_AVX2 1
#define IRIS_LANES_AVX2 __attribute__((target("avx2")))
#else
#define IRIS_LANES_HAVE_AVX2 0
#define IRIS_LANES_AVX2
#endif

/// Tests only: force the baseline build even where AVX2 is available.
inline std::atomic<bool> forceBaseline{false};

/// Whether lane kernels take their AVX2 build (CPU support, and not forced off).
inline bool useAvx2() {
#if IRIS_LANES_HAVE_AVX2
    static const bool cpu = (__builtin_cpu_init(), __builtin_cpu_supports("avx2"));
    return cpu && !forceBaseline.load(std::memory_order_relaxed);
#else
    return false;
#endif
}

/// useAvx2() for a loop over `lanes` floats: below 8 lanes (N ≤ 4) the 8-wide build only adds
/// its set-up and remainder code (more instructions than the 4-wide baseline on the thin-film scene).
inline bool useAvx2For(int lanes) { return lanes >= 8 && useAvx2(); }

#define IRIS_LANES_UNPAREN(...) __VA_ARGS__
/// Defines name##Avx2 (compiled for AVX2) and name##Baseline, each the always-inline `body`
/// compiled for its target, and the dispatcher `ret name(bool avx2, params...)`; `params` is the
/// parenthesised parameter list and `args` the parenthesised argument names. Use it inside an
/// unnamed namespace of the kernel's .cpp file.
#define IRIS_LANES_KERNEL(ret, name, body, params, args)                              \
    IRIS_LANES_AVX2 ret name##Avx2 params { return body args; }                       \
    ret name##Baseline params { return body args; }                                   \
    IRIS_LANES_INLINE ret name(bool avx2, IRIS_LANES_UNPAREN params) {                \
        return avx2 ? name##Avx2 args : name##Baseline args;                          \
    }

}  // namespace iris::lanes
