#include "spectral/mueller.h"

namespace iris::mueller {

Mueller4f multiply(const Mueller4f& a, const Mueller4f& b) {
    Mueller4f r;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            for (int k = 0; k < 4; ++k) r.m[i][j] += a.m[i][k] * b.m[k][j];
    return r;
}

Mueller4f rotatedElement(float theta, const Mueller4f& m) {
    // Rᵀ(θ) M R(θ) (Collett ch. 5 eq. 45; Mitsuba 3 mueller::rotated_element).
    const Mueller4f r = rotator(BasisRotation::ofAngle(theta));
    Mueller4f rt;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) rt.m[i][j] = r.m[j][i];
    return multiply(rt, multiply(m, r));
}

MuellerSpectrum rotateBases(const MuellerSpectrum& m, const BasisRotation& in, const BasisRotation& out) {
    if (m.depolarizing()) return m;  // only (0, 0), which no rotation touches
    return m.interfaceLayout() ? rotatedInterface(m, in, out) : rotateBasesDense(m, in, out);
}

MuellerSpectrum rotateBasesDense(const MuellerSpectrum& m, const BasisRotation& in, const BasisRotation& out) {
    if (m.depolarizing()) return m;
    MuellerSpectrum r = m;
    // Lane loops over the entries' padded lanes (no SampledSpectrum temporaries: this runs at every
    // polarized vertex with a dense matrix); the same float operations in the same order as the
    // spectrum arithmetic they replace, so the same values.
    const int padded = SampledSpectrum::paddedSize(m.size());
    // R_out · M (rotator rows 1 and 2: [c, s] and [−s, c]; Mitsuba 3 mueller::rotate_mueller_basis).
    for (int j = 0; j < 4; ++j) {
        const float *a = m(1, j).lanes(), *b = m(2, j).lanes();
        float *r1 = r(1, j).lanes(), *r2 = r(2, j).lanes();
        for (int l = 0; l < padded; ++l) {
            r1[l] = a[l] * out.c2 + b[l] * out.s2;
            r2[l] = b[l] * out.c2 - a[l] * out.s2;
        }
    }
    // (R_out M) · R_inᵀ (columns 1 and 2).
    for (int i = 0; i < 4; ++i) {
        float *c1 = r(i, 1).lanes(), *c2 = r(i, 2).lanes();
        for (int l = 0; l < padded; ++l) {
            const float a = c1[l], b = c2[l];
            c1[l] = a * in.c2 + b * in.s2;
            c2[l] = b * in.c2 - a * in.s2;
        }
    }
    return r;
}

MuellerSpectrum rotatedInterface(const MuellerSpectrum& m, const BasisRotation& in, const BasisRotation& out) {
    // rotateBasesDense's operations on [[A, B, 0, 0], [B, A, 0, 0], [0, 0, C, −D], [0, 0, D, C]]
    // without the products with its zeros (x·c + 0·s = x·c), in the same order and float lane by
    // lane, so that every entry has the dense product's value (up to the sign of a zero). Rows 0
    // and 3 of R_out M are M's, and (0, 0), (0, 3), (3, 0), (3, 3) stay M's (A, 0, 0, C): the
    // result starts as a copy of m (cheaper than zero-filling 16 spectra).
    MuellerSpectrum r = m;
    SampledSpectrum &r01 = r(0, 1), &r02 = r(0, 2), &r10 = r(1, 0), &r11 = r(1, 1), &r12 = r(1, 2), &r13 = r(1, 3);
    SampledSpectrum &r20 = r(2, 0), &r21 = r(2, 1), &r22 = r(2, 2), &r23 = r(2, 3), &r31 = r(3, 1), &r32 = r(3, 2);
    const float oc = out.c2, os = out.s2, ic = in.c2, is = in.s2;
    for (int j = 0; j < m.size(); ++j) {
        const float A = m(0, 0)[j], B = m(0, 1)[j], C = m(2, 2)[j], mD = m(2, 3)[j], D = m(3, 2)[j];
        // R_out · M: rows 1 and 2 become (a c + b s, b c − a s) of their old values (Collett ch. 5 eq. 43).
        const float a1 = A * oc, c1 = C * os, a2 = -(A * os), c2 = C * oc;
        r10[j] = B * oc;
        r20[j] = -(B * os);
        r13[j] = mD * os;
        r23[j] = mD * oc;
        // (R_out M) · R_inᵀ: columns 1 and 2 become (a c + b s, b c − a s) of their old values.
        r01[j] = B * ic;
        r02[j] = -(B * is);
        r11[j] = a1 * ic + c1 * is;
        r12[j] = c1 * ic - a1 * is;
        r21[j] = a2 * ic + c2 * is;
        r22[j] = c2 * ic - a2 * is;
        r31[j] = D * is;
        r32[j] = D * ic;
    }
    return r;
}

}  // namespace iris::mueller
