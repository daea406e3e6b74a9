// The fast exact single-film Airy kernel (film_stack.h airySingleFilmFast), inline so that
// FilmCoating's per-path loop over wavelengths (spectral/film_coating.cpp) can inline it; see
// film_stack.h for the formulation and docs/thin_film.md §8.
#pragma once

#include <algorithm>
#include <cmath>

#include "spectral/film_stack.h"

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

}  // namespace airy_detail

inline bool airySingleFilmFastInline(double cosThetaIncident, double incidentIor, const AiryFilmConstants& film,
                        const SquaredIndex& substrate, FilmStackResult& out) {
    using namespace airy_detail;
    const double c = std::clamp(cosThetaIncident, 0.0, 1.0);
    const double s = incidentIor * std::sqrt(std::max(0.0, 1.0 - c * c));
    const double s2 = s * s;
    const double q0 = incidentIor * c;
    // Normal wave numbers q_j = sqrt(ñ_j² − s²), Im q_j ≥ 0 (Born & Wolf §1.5, ch. 14).
    const complexd q1 = waveFromRadicand(film.n1sq - s2);
    const complexd q2 = waveFromRadicand(substrate.sq - s2);
    // E = e^{2iδ}, δ = k0 d q1 (Born & Wolf §1.6.4), enters only as P = 1 + E and M = 1 − E, and
    // through |E| = e^{−2 Im δ} ≤ 1. With the half angle h = Re δ (one sin/cos pair, no exp for a
    // lossless film): 1 ± cos 2h = 2cos²h, 2sin²h and sin 2h = 2 sin h cos h, so
    //   P = (1 − |E|) + |E|·2cos²h + i|E|·2 sin h cos h,   M = (1 − |E|) + |E|·2sin²h − i|E|·2 sin h cos h,
    // both without cancellation (1 − |E| = −expm1(−2 Im δ) ≥ 0).
    const double h = film.k0d * q1.real(), di = film.k0d * q1.imag();
    const double absE = di == 0 ? 1.0 : std::exp(-2.0 * di);
    const double oneMinusAbsE = di == 0 ? 0.0 : -std::expm1(-2.0 * di);
    const double sh = std::sin(h), ch = std::cos(h);
    const double sc = 2.0 * absE * sh * ch;
    const complexd P(oneMinusAbsE + 2.0 * absE * ch * ch, sc);
    const complexd M(oneMinusAbsE + 2.0 * absE * sh * sh, -sc);
    // Tilted admittances (Macleod ch. 2): y_s = q, y_p = q/ñ².
    const double y0[2] = {q0, q0 / (incidentIor * incidentIor)};
    const complexd y1[2] = {q1, cmul(q1, film.invN1sq)};
    const complexd y2[2] = {q2, cmul(q2, substrate.inv)};
    double R[2], T[2];
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
        R[k] = cnorm(num) / dd;
        // T = Re(y2)/y0 |t|² (Macleod ch. 2) = 16 y0 Re(y2) |y1|² |E| / |den|², since |e^{iδ}|² = |E|.
        T[k] = 16.0 * y0[k] * y2[k].real() * cnorm(y1[k]) * absE / dd;
        if (!std::isfinite(R[k]) || !std::isfinite(T[k])) return false;
    }
    // Same clamps as the reference (combine with clampR, transmittance()).
    out.Rs = std::min(1.0, R[0]);
    out.Rp = std::min(1.0, R[1]);
    out.Ts = std::clamp(T[0], 0.0, 1.0);
    out.Tp = std::clamp(T[1], 0.0, 1.0);
    return true;
}

}  // namespace iris
