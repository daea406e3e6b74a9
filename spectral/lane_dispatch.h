// Run-time choice between two builds of a per-wavelength lane loop: the baseline x86-64 (SSE2,
// 4 floats per instruction) and AVX2 (8 floats per instruction, no FMA: the floating-point
// operations and their order are the same, so the two builds give bit-identical results;
// tests/spectral/test_spectral_lanes.cpp runs both and compares). The binary stays runnable on any x86-64
// (no -march flag): the AVX2 build is only called when the CPU reports AVX2. A kernel is written
// once as an always-inline body and instantiated twice:
//
//   IRIS_LANES_INLINE void bodyOf(...) { for (...) ... }
//   IRIS_LANES_AVX2 void kernelAvx2(...) { bodyOf(...); }
//   void kernelBaseline(...) { bodyOf(...); }
//   ... lanes::useAvx2() ? kernelAvx2(...) : kernelBaseline(...);
#pragma once

#include <atomic>

namespace iris::lanes {

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define IRIS_LANES_HAVE_AVX2 1
#define IRIS_LANES_AVX2 __attribute__((target("avx2")))
#else
#define IRIS_LANES_HAVE_AVX2 0
#define IRIS_LANES_AVX2
#endif
#define IRIS_LANES_INLINE [[gnu::always_inline]] inline

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

}  // namespace iris::lanes
