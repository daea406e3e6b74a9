// The exact single-film Airy kernel (spectral/thin_film_airy.h) over all wavelengths of a path at once:
// structure-of-arrays inputs, four wavelengths per lane group (lanes::Double4, spectral/lanes.h; an
// SSE2 and an AVX2 build, spectral/lane_dispatch.h). ThinFilmCoating (materials/thin_film_coating.cpp)
// evaluates every reflectance / transmittance of a single exact film through it. Same formulation
// as airySingleFilmFastAt, lane by lane, except the complex square root of an absorbing medium
// (Kahan's form instead of std::sqrt): the lanes agree with the scalar kernel to relative 1e-14,
// and bit for bit for lossless media (docs/thin_film.md §8).
#pragma once

#include <cstdint>

namespace iris {

/// Wavelengths per SIMD group; every array of AiryBatchInput is padded to a multiple of it.
constexpr int kAiryLanes = 4;
constexpr int airyPadded(int n) { return (n + kAiryLanes - 1) / kAiryLanes * kAiryLanes; }

/// Per-wavelength inputs (SoA, each array airyPadded(n) long; padding lanes hold any finite values,
/// e.g. copies of the last entry). Film: ñ1², 1/ñ1², k0 d = 2π d/λ. Substrate (the medium below the
/// film as seen from the incident side): ñ2², 1/ñ2². Incident medium: s² = (n0 sinθ0)² and the
/// admittances y0s = n0 cosθ0, y0p = n0 cosθ0 / n0² (film_airy.h AiryAngle).
struct AiryBatchInput {
    const double *n1Re, *n1Im, *inv1Re, *inv1Im, *k0d;
    const double *n2Re, *n2Im, *inv2Re, *inv2Im;
    const double *s2, *y0s, *y0p;
};

/// Outputs (each array airyPadded(n) long): R and T for s and p, clamped as airySingleFilmFastAt
/// clamps them (R ≤ 1, 0 ≤ T ≤ 1). When crossR and crossT are set (real and imaginary parts), the
/// polarized mode's terms instead: clampedPolarization(airySingleFilmPolarizationAt(...))
/// (spectral/thin_film_polarization.h), i.e. T also ≤ 1 − R, and the cross terms r_s r_p* and
/// √(T_s T_p)·phase(t_s t_p*) bounded by √ of the clamped powers.
struct AiryBatchOutput {
    double *Rs, *Rp, *Ts, *Tp;
    double *crossRRe = nullptr, *crossRIm = nullptr, *crossTRe = nullptr, *crossTIm = nullptr;
};

/// Evaluate entries [0, n), n ≤ 32. Returns a bit mask of the entries where the closed form declined
/// (den vanishes or underflows: q1 = 0 exactly; or a non-finite result): the caller evaluates those
/// with the transfer matrix, exactly where airySingleFilmFastAt returns false. Their outputs are
/// unspecified. Tested lane by lane against airySingleFilmFastAt in tests/spectral/test_thin_film_airy_batch.cpp.
uint32_t airySingleFilmBatch(const AiryBatchInput& in, int n, const AiryBatchOutput& out);

}  // namespace iris
