#include "spectral/thin_film_airy_batch.h"

#include <cmath>

#include "spectral/thin_film_airy.h"
#include "spectral/lane_dispatch.h"

namespace iris {

namespace {

// Four doubles per group (spectral/lanes.h): the baseline x86-64 build lowers them to pairs of SSE2
// instructions, the AVX2 build (spectral/lane_dispatch.h, chosen at run time) to single 256-bit
// ones, with the same IEEE operations in either build. Each lane performs the operations of the
// scalar airySingleFilmFastAt except the complex square root (waveFromRadicand below), so the
// lanes agree with it to rounding (relative 1e-14, docs/thin_film.md §8), and exactly for real
// radicands (lossless film and substrate, propagating or evanescent).
using lanes::broadcast;
using lanes::Double4;
using lanes::Long4;
using lanes::select;
static_assert(kAiryLanes == 4);
// Everything below is inlined into each build, so that each is compiled for its own target.

struct vcomplex {
    Double4 re, im;
};
IRIS_LANES_INLINE vcomplex cmul(vcomplex a, vcomplex b) { return {a.re * b.re - a.im * b.im, a.re * b.im + a.im * b.re}; }
IRIS_LANES_INLINE Double4 cnorm(vcomplex a) { return a.re * a.re + a.im * a.im; }
IRIS_LANES_INLINE vcomplex conj(vcomplex a) { return {a.re, -a.im}; }

/// z/|z| lane-wise, 0 where |z| underflows to 0 (thin_film_polarization.cpp unitPhase).
IRIS_LANES_INLINE vcomplex unitPhase(vcomplex z) {
    const Double4 m = lanes::sqrt(cnorm(z));
    const Long4 some = m > 0;
    return {select(some, z.re / m, broadcast(0.0)), select(some, z.im / m, broadcast(0.0))};
}

/// c scaled down to magnitude `limit` where it exceeds it (clampedPolarization's bound).
IRIS_LANES_INLINE vcomplex bounded(vcomplex c, Double4 limit) {
    const Double4 m = lanes::sqrt(cnorm(c));
    const Long4 over = (m > limit) & (m > 0);
    const Double4 k = limit / m;
    return {select(over, c.re * k, c.re), select(over, c.im * k, c.im)};
}

/// clampedPolarization(airySingleFilmPolarizationAt(...)) (spectral/thin_film_polarization.cpp)
/// from the lanes' num, den, |den|², y1 and kernel-clamped R and T, with the same operations in the
/// same order: the powers, then T ≤ 1 − R, then the cross terms bounded by the clamped powers.
IRIS_LANES_INLINE void polarizedTerms(const vcomplex num[2], const vcomplex den[2], const Double4 dd[2], const vcomplex y1[2],
                                      Double4 Rs, Double4 Rp, Double4 Ts, Double4 Tp, const AiryBatchOutput& out, int i) {
    vcomplex r[2], phaseT[2];
    for (int k = 0; k < 2; ++k) {
        const vcomplex z = cmul(num[k], conj(den[k]));  // r = num/den = num·conj(den)/|den|²
        r[k] = {z.re / dd[k], z.im / dd[k]};
        phaseT[k] = unitPhase(cmul(y1[k], conj(den[k])));  // the phase of t ∝ y1/den
    }
    const vcomplex phase = cmul(phaseT[0], conj(phaseT[1]));
    const Double4 m = lanes::sqrt(lanes::max(broadcast(0.0), Ts * Tp));
    // clampedPowers (R is already in [0, 1]), then the bounds.
    const Double4 TsC = lanes::min(Ts, 1.0 - Rs), TpC = lanes::min(Tp, 1.0 - Rp);
    const vcomplex crossR = bounded(cmul(r[0], conj(r[1])), lanes::sqrt(Rs * Rp));
    const vcomplex crossT = bounded({m * phase.re, m * phase.im}, lanes::sqrt(TsC * TpC));
    lanes::store(out.Ts + i, TsC);
    lanes::store(out.Tp + i, TpC);
    lanes::store(out.crossRRe + i, crossR.re);
    lanes::store(out.crossRIm + i, crossR.im);
    lanes::store(out.crossTRe + i, crossT.re);
    lanes::store(out.crossTIm + i, crossT.im);
}

/// waveFromRadicand (film_airy.h) lane-wise: q = sqrt(z) on the decaying branch (Im q ≥ 0). A real
/// radicand takes the real square root (the same value as the scalar kernel, bit for bit); a complex
/// one the principal root from t = sqrt((|z| + |Re z|)/2) (Kahan's form: no cancellation), then the
/// branch with Im q ≥ 0.
IRIS_LANES_INLINE vcomplex waveFromRadicand(Double4 x, Double4 y) {
    const Double4 ax = lanes::abs(x);
    const Long4 real = y == 0;
    const Double4 m = select(real, ax, lanes::sqrt(x * x + y * y));  // |z|
    const Double4 t = lanes::sqrt(0.5 * (m + ax));               // real radicand: (|x| + |x|)/2 = |x| exactly
    const Double4 other = 0.5 * lanes::abs(y) / t;  // |y|/(2t)
    // Principal root: x ≥ 0 → (t, y/(2t)); x < 0 → (|y|/(2t), copysign(t, y)).
    Double4 re = select(x >= 0, t, other), im = select(x >= 0, lanes::copysign(other, y), lanes::copysign(t, y));
    // Decaying branch: Im q < 0 → −q (Im q = 0 only for y = 0, handled below).
    const Long4 flip = im < 0;
    re = select(flip, -re, re);
    im = select(flip, -im, im);
    // Real radicand: x ≥ 0 → (sqrt x, 0), x < 0 → (0, sqrt(−x)); t = sqrt(|x|) there.
    re = select(real, select(x >= 0, t, broadcast(0.0)), re);
    im = select(real, select(x >= 0, broadcast(0.0), t), im);
    return {re, im};
}

/// airy_detail::sinCos lane-wise for |x| ≤ 1e5 (the same reduction and polynomials,
/// airy_detail::sinCosReduced); the quadrant j mod 4 is read from the low bits of `shifted`. Lanes
/// with |x| > 1e5 or NaN are flagged in `big` for the caller.
IRIS_LANES_INLINE void sinCos(Double4 x, Double4& sinX, Double4& cosX, int& big) {
    big = lanes::bits(~(lanes::abs(x) <= 1e5));
    Double4 shifted, sr, cr;
    airy_detail::sinCosReduced(x, shifted, sr, cr);
    const Long4 quadrant = (Long4)shifted & 3;
    // x = r + j·π/2: quadrant 0 (sr, cr), 1 (cr, −sr), 2 (−sr, −cr), 3 (−cr, sr).
    const Long4 odd = (quadrant & 1) != 0;
    const Double4 s = select(odd, cr, sr), c = select(odd, sr, cr);
    sinX = select((quadrant & 2) != 0, -s, s);
    cosX = select(((quadrant + 1) & 2) != 0, -c, c);
}

/// One group of four lanes starting at entry i; returns the lanes (bits 0..3) that declined.
IRIS_LANES_INLINE int airyGroup(const AiryBatchInput& in, int i, const AiryBatchOutput& out) {
    const Double4 s2 = lanes::load(in.s2 + i);
    // q_j = sqrt(ñ_j² − s²), Im q_j ≥ 0 (Born & Wolf §1.5, ch. 14).
    const vcomplex q1 = waveFromRadicand(lanes::load(in.n1Re + i) - s2, lanes::load(in.n1Im + i));
    const vcomplex q2 = waveFromRadicand(lanes::load(in.n2Re + i) - s2, lanes::load(in.n2Im + i));
    // δ = k0 d q1 (Born & Wolf §1.6.4); |E| = e^{−2 Im δ} and 1 − |E| per lane through libm (only
    // absorbing films have Im δ ≠ 0).
    const Double4 k0d = lanes::load(in.k0d + i);
    const Double4 h = k0d * q1.re, di = k0d * q1.im;
    Double4 absE = broadcast(1.0), oneMinusAbsE = broadcast(0.0);
    if (lanes::bits(di != 0)) {
        for (int l = 0; l < 4; ++l) {
            if (di[l] == 0) continue;
            absE[l] = std::exp(-2.0 * di[l]);
            oneMinusAbsE[l] = -std::expm1(-2.0 * di[l]);
        }
    }
    Double4 sh, ch;
    int big;
    sinCos(h, sh, ch, big);
    if (big) {
        for (int l = 0; l < 4; ++l) {
            if (!(big >> l & 1)) continue;
            sh[l] = std::sin(h[l]);
            ch[l] = std::cos(h[l]);
        }
    }
    // P = 1 + E, M = 1 − E from the half angle without cancellation (film_airy.h).
    const Double4 sc = 2.0 * absE * sh * ch;
    const vcomplex P{oneMinusAbsE + 2.0 * absE * ch * ch, sc};
    const vcomplex M{oneMinusAbsE + 2.0 * absE * sh * sh, -sc};
    // Tilted admittances (Macleod ch. 2): y_s = q, y_p = q/ñ².
    const Double4 y0[2] = {lanes::load(in.y0s + i), lanes::load(in.y0p + i)};
    const vcomplex y1[2] = {q1, cmul(q1, {lanes::load(in.inv1Re + i), lanes::load(in.inv1Im + i)})};
    const vcomplex y2[2] = {q2, cmul(q2, {lanes::load(in.inv2Re + i), lanes::load(in.inv2Im + i)})};
    Long4 bad = {0, 0, 0, 0};
    Double4 R[2], T[2], dd[2];
    vcomplex num[2], den[2];
    for (int k = 0; k < 2; ++k) {
        // num = y1 (y0 − y2) P + (y0 y2 − y1²) M,  den = y1 (y0 + y2) P + (y0 y2 + y1²) M
        // (the expanded Airy sum of film_airy.h, Born & Wolf §1.5.2 / §1.6.4).
        const vcomplex y1sq = cmul(y1[k], y1[k]);
        const vcomplex y02{y0[k] * y2[k].re, y0[k] * y2[k].im};
        num[k] = [&] {
            const vcomplex a = cmul(cmul(y1[k], {y0[k] - y2[k].re, -y2[k].im}), P);
            const vcomplex b = cmul({y02.re - y1sq.re, y02.im - y1sq.im}, M);
            return vcomplex{a.re + b.re, a.im + b.im};
        }();
        den[k] = [&] {
            const vcomplex a = cmul(cmul(y1[k], {y0[k] + y2[k].re, y2[k].im}), P);
            const vcomplex b = cmul({y02.re + y1sq.re, y02.im + y1sq.im}, M);
            return vcomplex{a.re + b.re, a.im + b.im};
        }();
        dd[k] = cnorm(den[k]);
        R[k] = cnorm(num[k]) / dd[k];
        // T = Re(y2)/y0 |t|² = 16 y0 Re(y2) |y1|² |E| / |den|² (Macleod ch. 2).
        T[k] = 16.0 * y0[k] * y2[k].re * cnorm(y1[k]) * absE / dd[k];
        bad |= ~((dd[k] > 1e-250) & (R[k] - R[k] == 0) & (T[k] - T[k] == 0));  // x − x ≠ 0: inf or NaN
    }
    const Double4 Ts = lanes::min(lanes::max(T[0], broadcast(0.0)), broadcast(1.0));  // std::clamp(T, 0, 1)
    const Double4 Tp = lanes::min(lanes::max(T[1], broadcast(0.0)), broadcast(1.0));
    const Double4 Rs = lanes::min(broadcast(1.0), R[0]), Rp = lanes::min(broadcast(1.0), R[1]);
    lanes::store(out.Rs + i, Rs);
    lanes::store(out.Rp + i, Rp);
    if (out.crossRRe) {
        polarizedTerms(num, den, dd, y1, Rs, Rp, Ts, Tp, out, i);
    } else {
        lanes::store(out.Ts + i, Ts);
        lanes::store(out.Tp + i, Tp);
    }
    return lanes::bits(bad);
}

IRIS_LANES_INLINE uint32_t airyBatchBody(const AiryBatchInput& in, int n, const AiryBatchOutput& out) {
    uint32_t declined = 0;
    for (int i = 0; i < n; i += kAiryLanes) declined |= uint32_t(airyGroup(in, i, out)) << i;
    return n >= 32 ? declined : declined & ((1u << n) - 1);
}

IRIS_LANES_KERNEL(uint32_t, airyBatch, airyBatchBody, (const AiryBatchInput& in, int n, const AiryBatchOutput& out),
                  (in, n, out))

}  // namespace

uint32_t airySingleFilmBatch(const AiryBatchInput& in, int n, const AiryBatchOutput& out) {
    // Four doubles fill one AVX2 register, so the AVX2 build pays off from the first group.
    return airyBatch(lanes::useAvx2(), in, n, out);
}

}  // namespace iris
