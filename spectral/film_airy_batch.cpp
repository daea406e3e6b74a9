#include "spectral/film_airy_batch.h"

#include <cmath>
#include <cstring>

#include "spectral/film_airy.h"
#include "spectral/lane_dispatch.h"

namespace iris {

namespace {

// GCC/Clang vector extensions: four doubles, operated on element-wise. The baseline x86-64 build
// lowers them to pairs of SSE2 instructions; the AVX2 build (spectral/lane_dispatch.h, chosen at run
// time) to single 256-bit ones. Only IEEE add, sub, mul, div and sqrt (correctly rounded, and no
// FMA contraction: neither build enables FMA) appear, so every lane computes exactly what the scalar
// airySingleFilmFastAt computes, in either build.
typedef double v4d __attribute__((vector_size(32)));
typedef long long v4i __attribute__((vector_size(32)));
static_assert(kAiryLanes == 4);
// Everything below is inlined into each build, so that each is compiled for its own target.

IRIS_LANES_INLINE v4d load(const double* p) {
    v4d v;
    std::memcpy(&v, p, sizeof v);
    return v;
}
IRIS_LANES_INLINE void store(double* p, v4d v) { std::memcpy(p, &v, sizeof v); }
IRIS_LANES_INLINE v4d splat(double x) { return v4d{x, x, x, x}; }
IRIS_LANES_INLINE v4d sel(v4i m, v4d a, v4d b) { return m ? a : b; }
IRIS_LANES_INLINE v4d vsqrt(v4d a) {
    v4d r;
    for (int i = 0; i < 4; ++i) r[i] = __builtin_sqrt(a[i]);  // one sqrtpd with -fno-math-errno
    return r;
}
IRIS_LANES_INLINE v4d vabs(v4d a) { return (v4d)((v4i)a & 0x7fffffffffffffffLL); }
IRIS_LANES_INLINE v4d vcopysign(v4d mag, v4d sgn) {
    return (v4d)(((v4i)mag & 0x7fffffffffffffffLL) | ((v4i)sgn & (long long)0x8000000000000000ULL));
}
IRIS_LANES_INLINE v4d vmin(v4d a, v4d b) { return sel(b < a, b, a); }  // std::min(a, b)
IRIS_LANES_INLINE v4d vmax(v4d a, v4d b) { return sel(a < b, b, a); }  // std::max(a, b)
IRIS_LANES_INLINE int laneMask(v4i m) { return int(m[0] & 1) | int(m[1] & 2) | int(m[2] & 4) | int(m[3] & 8); }

struct vcomplex {
    v4d re, im;
};
IRIS_LANES_INLINE vcomplex cmul(vcomplex a, vcomplex b) { return {a.re * b.re - a.im * b.im, a.re * b.im + a.im * b.re}; }
IRIS_LANES_INLINE v4d cnorm(vcomplex a) { return a.re * a.re + a.im * a.im; }

/// waveFromRadicand (film_airy.h) lane-wise: q = sqrt(z) on the decaying branch (Im q ≥ 0). A real
/// radicand takes the real square root (the same value as the scalar kernel, bit for bit); a complex
/// one the principal root from t = sqrt((|z| + |Re z|)/2) (Kahan's form: no cancellation), then the
/// branch with Im q ≥ 0.
IRIS_LANES_INLINE vcomplex waveFromRadicand(v4d x, v4d y) {
    const v4d ax = vabs(x);
    const v4i real = y == 0;
    const v4d m = sel(real, ax, vsqrt(x * x + y * y));  // |z|
    const v4d t = vsqrt(0.5 * (m + ax));               // real radicand: (|x| + |x|)/2 = |x| exactly
    const v4d other = 0.5 * vabs(y) / t;  // |y|/(2t)
    // Principal root: x ≥ 0 → (t, y/(2t)); x < 0 → (|y|/(2t), copysign(t, y)).
    v4d re = sel(x >= 0, t, other), im = sel(x >= 0, vcopysign(other, y), vcopysign(t, y));
    // Decaying branch: Im q < 0 → −q (Im q = 0 only for y = 0, handled below).
    const v4i flip = im < 0;
    re = sel(flip, -re, re);
    im = sel(flip, -im, im);
    // Real radicand: x ≥ 0 → (sqrt x, 0), x < 0 → (0, sqrt(−x)); t = sqrt(|x|) there.
    re = sel(real, sel(x >= 0, t, splat(0.0)), re);
    im = sel(real, sel(x >= 0, splat(0.0), t), im);
    return {re, im};
}

/// airy_detail::sinCos lane-wise for |x| ≤ 1e5 (the same reduction and polynomials,
/// airy_detail::sinCosReduced); the quadrant j mod 4 is read from the low bits of `shifted`. Lanes
/// with |x| > 1e5 or NaN are flagged in `big` for the caller.
IRIS_LANES_INLINE void sinCos(v4d x, v4d& sinX, v4d& cosX, int& big) {
    big = laneMask(~(vabs(x) <= 1e5));
    v4d shifted, sr, cr;
    airy_detail::sinCosReduced(x, shifted, sr, cr);
    const v4i quadrant = (v4i)shifted & 3;
    // x = r + j·π/2: quadrant 0 (sr, cr), 1 (cr, −sr), 2 (−sr, −cr), 3 (−cr, sr).
    const v4i odd = (quadrant & 1) != 0;
    const v4d s = sel(odd, cr, sr), c = sel(odd, sr, cr);
    sinX = sel((quadrant & 2) != 0, -s, s);
    cosX = sel(((quadrant + 1) & 2) != 0, -c, c);
}

/// One group of four lanes starting at entry i; returns the lanes (bits 0..3) that declined.
IRIS_LANES_INLINE int airyGroup(const AiryBatchInput& in, int i, const AiryBatchOutput& out) {
    const v4d s2 = load(in.s2 + i);
    // q_j = sqrt(ñ_j² − s²), Im q_j ≥ 0 (Born & Wolf §1.5, ch. 14).
    const vcomplex q1 = waveFromRadicand(load(in.n1Re + i) - s2, load(in.n1Im + i));
    const vcomplex q2 = waveFromRadicand(load(in.n2Re + i) - s2, load(in.n2Im + i));
    // δ = k0 d q1 (Born & Wolf §1.6.4); |E| = e^{−2 Im δ} and 1 − |E| per lane through libm (only
    // absorbing films have Im δ ≠ 0).
    const v4d k0d = load(in.k0d + i);
    const v4d h = k0d * q1.re, di = k0d * q1.im;
    v4d absE = splat(1.0), oneMinusAbsE = splat(0.0);
    if (laneMask(di != 0)) {
        for (int l = 0; l < 4; ++l) {
            if (di[l] == 0) continue;
            absE[l] = std::exp(-2.0 * di[l]);
            oneMinusAbsE[l] = -std::expm1(-2.0 * di[l]);
        }
    }
    v4d sh, ch;
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
    const v4d sc = 2.0 * absE * sh * ch;
    const vcomplex P{oneMinusAbsE + 2.0 * absE * ch * ch, sc};
    const vcomplex M{oneMinusAbsE + 2.0 * absE * sh * sh, -sc};
    // Tilted admittances (Macleod ch. 2): y_s = q, y_p = q/ñ².
    const v4d y0[2] = {load(in.y0s + i), load(in.y0p + i)};
    const vcomplex y1[2] = {q1, cmul(q1, {load(in.inv1Re + i), load(in.inv1Im + i)})};
    const vcomplex y2[2] = {q2, cmul(q2, {load(in.inv2Re + i), load(in.inv2Im + i)})};
    v4i bad = {0, 0, 0, 0};
    v4d R[2], T[2];
    for (int k = 0; k < 2; ++k) {
        // num = y1 (y0 − y2) P + (y0 y2 − y1²) M,  den = y1 (y0 + y2) P + (y0 y2 + y1²) M
        // (the expanded Airy sum of film_airy.h, Born & Wolf §1.5.2 / §1.6.4).
        const vcomplex y1sq = cmul(y1[k], y1[k]);
        const vcomplex y02{y0[k] * y2[k].re, y0[k] * y2[k].im};
        const vcomplex num = [&] {
            const vcomplex a = cmul(cmul(y1[k], {y0[k] - y2[k].re, -y2[k].im}), P);
            const vcomplex b = cmul({y02.re - y1sq.re, y02.im - y1sq.im}, M);
            return vcomplex{a.re + b.re, a.im + b.im};
        }();
        const vcomplex den = [&] {
            const vcomplex a = cmul(cmul(y1[k], {y0[k] + y2[k].re, y2[k].im}), P);
            const vcomplex b = cmul({y02.re + y1sq.re, y02.im + y1sq.im}, M);
            return vcomplex{a.re + b.re, a.im + b.im};
        }();
        const v4d dd = cnorm(den);
        R[k] = cnorm(num) / dd;
        // T = Re(y2)/y0 |t|² = 16 y0 Re(y2) |y1|² |E| / |den|² (Macleod ch. 2).
        T[k] = 16.0 * y0[k] * y2[k].re * cnorm(y1[k]) * absE / dd;
        bad |= ~((dd > 1e-250) & (R[k] - R[k] == 0) & (T[k] - T[k] == 0));  // x − x ≠ 0: inf or NaN
    }
    store(out.Rs + i, vmin(splat(1.0), R[0]));
    store(out.Rp + i, vmin(splat(1.0), R[1]));
    store(out.Ts + i, vmin(vmax(T[0], splat(0.0)), splat(1.0)));  // std::clamp(T, 0, 1)
    store(out.Tp + i, vmin(vmax(T[1], splat(0.0)), splat(1.0)));
    return laneMask(bad);
}

IRIS_LANES_INLINE uint32_t airyBatchBody(const AiryBatchInput& in, int n, const AiryBatchOutput& out) {
    uint32_t declined = 0;
    for (int i = 0; i < n; i += kAiryLanes) declined |= uint32_t(airyGroup(in, i, out)) << i;
    return n >= 32 ? declined : declined & ((1u << n) - 1);
}

IRIS_LANES_AVX2 uint32_t airyBatchAvx2(const AiryBatchInput& in, int n, const AiryBatchOutput& out) {
    return airyBatchBody(in, n, out);
}
uint32_t airyBatchBaseline(const AiryBatchInput& in, int n, const AiryBatchOutput& out) {
    return airyBatchBody(in, n, out);
}

}  // namespace

uint32_t airySingleFilmBatch(const AiryBatchInput& in, int n, const AiryBatchOutput& out) {
    // Four doubles fill one AVX2 register, so the AVX2 build pays off from the first group.
    return lanes::useAvx2() ? airyBatchAvx2(in, n, out) : airyBatchBaseline(in, n, out);
}

}  // namespace iris
