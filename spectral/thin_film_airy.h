// The fast exact single-film Airy kernel (thin_film_stack.h airySingleFilmFast), inline so that
// ThinFilmCoating's per-path loop over wavelengths (materials/thin_film_coating.cpp) can inline it; see
// film_stack.h for the formulation and docs/thin_film.md §8.
#pragma once

#include <algorithm>
#include <cmath>

#include "spectral/thin_film_stack.h"

namespace iris {
namespace airy_detail {

// Complex product and squared modulus in plain real arithmetic. std::complex's operators follow C
// Annex G (inf/NaN recovery through libgcc's __muldc3/__divdc3); the fast Airy path never needs
// that, since it checks its results for finiteness and falls back to the reference otherwise.
inline complexd cmul(complexd a, complexd b) {
    return {a.real() * b.real() - a.imag() * b.imag(), a.real() * b.imag() + a.imag() * b.real()};
}
inline double cnorm(complexd a) { return a.real() * a.real() + a.imag() * a.imag(); }

/// q = sqrt(radicand) on the decaying branch (as normalWaveNumber). A real radicand (lossless
/// medium) takes a real square root: propagating (q real) or evanescent (q = i·sqrt(−radicand)),
/// the values glibc's csqrt returns for a zero imaginary part, up to the sign of zero.
inline complexd waveFromRadicand(complexd z) {
    if (z.imag() == 0) return z.real() >= 0 ? complexd(std::sqrt(z.real()), 0.0) : complexd(0.0, std::sqrt(-z.real()));
    complexd q = std::sqrt(z);
    if (q.imag() < 0 || (q.imag() == 0 && q.real() < 0)) q = -q;
    return q;
}

/// The argument reduction and polynomials of sinCos below, shared with the batched kernel
/// (spectral/thin_film_airy_batch.cpp; T = double or a vector of doubles): Cody–Waite reduction
/// x = j·π/2 + r with π/2 split into three parts (the 33-bit pieces and tail of fdlibm's
/// __ieee754_rem_pio2, so j·p1 and j·p2 are exact for |j| < 2²⁰), then the Taylor series of sin r to
/// r¹⁵ and cos r to r¹⁶ on |r| ≤ π/4 (truncation < 5e-17). `shifted` = x·2/π + 1.5·2⁵² holds j as an
/// integer in its last mantissa bits; j = shifted − 1.5·2⁵².
constexpr double kRoundToInteger = 0x1.8p52;  // adding it rounds to an integer
template <typename T>
[[gnu::always_inline]] inline void sinCosReduced(T x, T& shifted, T& sinR, T& cosR) {
    constexpr double kTwoOverPi = 0x1.45f306dc9c883p-1;
    constexpr double kPio2_1 = 0x1.921fb544p+0;         // first 33 bits of π/2
    constexpr double kPio2_2 = 0x1.0b4611a6p-34;        // next 33 bits
    constexpr double kPio2_2t = 0x1.3198a2e037073p-69;  // π/2 − kPio2_1 − kPio2_2
    shifted = x * kTwoOverPi + kRoundToInteger;
    const T j = shifted - kRoundToInteger;  // nearest integer to x·2/π
    const T r = ((x - j * kPio2_1) - j * kPio2_2) - j * kPio2_2t;
    const T z = r * r;
    // Taylor coefficients (−1)^k/(2k+1)! and (−1)^k/(2k)!.
    sinR = r + r * z * (-1.0 / 6 + z * (1.0 / 120 + z * (-1.0 / 5040 + z * (1.0 / 362880 +
           z * (-1.0 / 39916800 + z * (1.0 / 6227020800.0 + z * (-1.0 / 1307674368000.0)))))));
    cosR = 1.0 + z * (-0.5 + z * (1.0 / 24 + z * (-1.0 / 720 + z * (1.0 / 40320 + z * (-1.0 / 3628800 +
           z * (1.0 / 479001600 + z * (-1.0 / 87178291200.0 + z * (1.0 / 20922789888000.0))))))));
}

/// sin x and cos x together, inline (one polynomial pair instead of a libm sincos call), for the
/// Airy phase: sinCosReduced, then the quadrant j mod 4. |x| > 1e5 (films thicker than ~1 mm):
/// std::sin / std::cos. Agreement with glibc: tests/materials/test_thin_film_fast.cpp (ThinFilmFastPath.SinCosMatchesLibm).
inline void sinCos(double x, double& sinX, double& cosX) {
    if (!(std::abs(x) <= 1e5)) {
        sinX = std::sin(x);
        cosX = std::cos(x);
        return;
    }
    double shifted, sr, cr;
    sinCosReduced(x, shifted, sr, cr);
    const double j = shifted - kRoundToInteger;
    switch (static_cast<long long>(j) & 3) {  // x = r + j·π/2
        case 0: sinX = sr; cosX = cr; break;
        case 1: sinX = cr; cosX = -sr; break;
        case 2: sinX = -sr; cosX = -cr; break;
        default: sinX = -cr; cosX = sr; break;
    }
}

}  // namespace airy_detail

/// The angle-dependent quantities of the incident medium, shared by all wavelengths of one
/// evaluation: s² = (n0 sinθ0)², and the incident admittances y0 = n0 cosθ0 (s), n0 cosθ0/n0² (p).
struct AiryAngle {
    double s2 = 0, y0s = 0, y0p = 0;
};
inline AiryAngle airyAngle(double cosThetaIncident, double incidentIor) {
    const double c = std::clamp(cosThetaIncident, 0.0, 1.0);
    const double s = incidentIor * std::sqrt(std::max(0.0, 1.0 - c * c));
    const double q0 = incidentIor * c;
    return {s * s, q0, q0 / (incidentIor * incidentIor)};
}

/// The fraction of the exact Airy sum for s (index 0) and p (index 1) as airySingleFilmFastAt
/// forms it: r = num/den, t = 4 y0 y1 e^{iδ}/den (y1 the film's tilted admittance), and the
/// unclamped powers R = |num|²/|den|², T = 16 y0 Re(y2) |y1|² |e^{2iδ}| / |den|². The polarized
/// mode's cross terms come from num, den and y1 (airySingleFilmPolarizationAt,
/// spectral/thin_film_polarization.h).
struct AiryFilmTerms {
    complexd num[2], den[2], y1[2];
    double dd[2];  // |den|²
    double R[2], T[2];
    /// The powers with the reference's clamps (airySingleFilmReference: combine with clampR, transmittance()).
    ThinFilmStackResult clampedPowers() const {
        return {std::min(1.0, R[0]), std::min(1.0, R[1]), std::clamp(T[0], 0.0, 1.0), std::clamp(T[1], 0.0, 1.0)};
    }
};

/// airySingleFilmFastAt's kernel without the clamps; false where it declines.
[[gnu::always_inline]] inline bool airySingleFilmTerms(const AiryAngle& angle, const AiryFilmConstants& film,
                                                       const SquaredIndex& substrate, AiryFilmTerms& out) {
    using namespace airy_detail;
    const double s2 = angle.s2;
    // Normal wave numbers q_j = sqrt(ñ_j² − s²), Im q_j ≥ 0 (Born & Wolf §1.5, ch. 14).
    const complexd q1 = waveFromRadicand(film.n1sq - s2);
    const complexd q2 = waveFromRadicand(substrate.sq - s2);
    // E = e^{2iδ}, δ = k0 d q1 (Born & Wolf §1.6.4), enters only as P = 1 + E and M = 1 − E, and
    // through |E| = e^{−2 Im δ} ≤ 1. With the half angle h = Re δ (one sin/cos pair, no exp for a
    // lossless film; airy_detail::sinCos): 1 ± cos 2h = 2cos²h, 2sin²h and sin 2h = 2 sin h cos h, so
    //   P = (1 − |E|) + |E|·2cos²h + i|E|·2 sin h cos h,   M = (1 − |E|) + |E|·2sin²h − i|E|·2 sin h cos h,
    // both without cancellation (1 − |E| = −expm1(−2 Im δ) ≥ 0).
    const double h = film.k0d * q1.real(), di = film.k0d * q1.imag();
    const double absE = di == 0 ? 1.0 : std::exp(-2.0 * di);
    const double oneMinusAbsE = di == 0 ? 0.0 : -std::expm1(-2.0 * di);
    double sh, ch;
    sinCos(h, sh, ch);
    const double sc = 2.0 * absE * sh * ch;
    const complexd P(oneMinusAbsE + 2.0 * absE * ch * ch, sc);
    const complexd M(oneMinusAbsE + 2.0 * absE * sh * sh, -sc);
    // Tilted admittances (Macleod ch. 2): y_s = q, y_p = q/ñ².
    const double y0[2] = {angle.y0s, angle.y0p};
    const complexd y1[2] = {q1, cmul(q1, film.invN1sq)};
    const complexd y2[2] = {q2, cmul(q2, substrate.inv)};
    for (int k = 0; k < 2; ++k) {
        // With r01 = (y0 − y1)/(y0 + y1), r12 = (y1 − y2)/(y1 + y2) (Born & Wolf §1.5.2, admittance
        // form), the Airy sum multiplied through by (y0 + y1)(y1 + y2) and expanded in P and M:
        //   r = num/den,  num = y1 (y0 − y2) P + (y0 y2 − y1²) M,  den = y1 (y0 + y2) P + (y0 y2 + y1²) M,
        //   t01 t12 e^{iδ}/(1 + r01 r12 E) = 4 y0 y1 e^{iδ}/den.
        // Both vanish like q1 at the film's critical angle (y1 ∝ q1, M ∝ δ ∝ q1), where the
        // unexpanded form is 0/0; here each term keeps its relative accuracy.
        const complexd y1sq = cmul(y1[k], y1[k]);
        const complexd y02 = y0[k] * y2[k];
        const complexd num = cmul(cmul(y1[k], y0[k] - y2[k]), P) + cmul(y02 - y1sq, M);
        const complexd den = cmul(cmul(y1[k], y0[k] + y2[k]), P) + cmul(y02 + y1sq, M);
        const double dd = cnorm(den);
        if (!(dd > 1e-250)) return false;  // q1 = 0 exactly (or y0 = y1 = 0): the caller uses the TMM
        out.R[k] = cnorm(num) / dd;
        // T = Re(y2)/y0 |t|² (Macleod ch. 2) = 16 y0 Re(y2) |y1|² |E| / |den|², since |e^{iδ}|² = |E|.
        out.T[k] = 16.0 * y0[k] * y2[k].real() * cnorm(y1[k]) * absE / dd;
        if (!std::isfinite(out.R[k]) || !std::isfinite(out.T[k])) return false;
        out.num[k] = num;
        out.den[k] = den;
        out.y1[k] = y1[k];
        out.dd[k] = dd;
    }
    return true;
}

/// airySingleFilmFast with the angle terms precomputed (ThinFilmCoating: once per evaluation for all
/// wavelengths).
inline bool airySingleFilmFastAt(const AiryAngle& angle, const AiryFilmConstants& film, const SquaredIndex& substrate,
                                 ThinFilmStackResult& out) {
    AiryFilmTerms t;
    if (!airySingleFilmTerms(angle, film, substrate, t)) return false;
    out = t.clampedPowers();
    return true;
}

}  // namespace iris
