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
    // R_out · M (rotator rows 1 and 2: [c, s] and [−s, c]; Mitsuba 3 mueller::rotate_mueller_basis).
    for (int j = 0; j < 4; ++j) {
        const SampledSpectrum a = m(1, j), b = m(2, j);
        r(1, j) = a * out.c2 + b * out.s2;
        r(2, j) = b * out.c2 - a * out.s2;
    }
    // (R_out M) · R_inᵀ (columns 1 and 2).
    for (int i = 0; i < 4; ++i) {
        const SampledSpectrum a = r(i, 1), b = r(i, 2);
        r(i, 1) = a * in.c2 + b * in.s2;
        r(i, 2) = b * in.c2 - a * in.s2;
    }
    return r;
}

MuellerSpectrum rotatedInterface(const MuellerSpectrum& m, const BasisRotation& in, const BasisRotation& out) {
    // rotateBasesDense's operations on [[A, B, 0, 0], [B, A, 0, 0], [0, 0, C, −D], [0, 0, D, C]]
    // without the products with its zeros (x·c + 0·s = x·c), in the same order, so that every
    // entry has the dense product's value (up to the sign of a zero).
    const SampledSpectrum &A = m(0, 0), &B = m(0, 1), &C = m(2, 2), &mD = m(2, 3), &D = m(3, 2);
    // R_out · M: rows 1 and 2 become (a c + b s, b c − a s) of their old values (Collett ch. 5 eq. 43).
    const SampledSpectrum r11 = A * out.c2, r12 = C * out.s2, r21 = -(A * out.s2), r22 = C * out.c2;
    // Rows 0 and 3 of R_out M are M's; (0, 0), (0, 3), (3, 0) and (3, 3) stay M's (A, 0, 0, C): a copy
    // of m for them is cheaper than zero-filling a new matrix.
    MuellerSpectrum r = m;
    r(1, 0) = B * out.c2;
    r(2, 0) = -(B * out.s2);
    r(1, 3) = mD * out.s2;
    r(2, 3) = mD * out.c2;
    // (R_out M) · R_inᵀ: columns 1 and 2 become (a c + b s, b c − a s) of their old values.
    r(0, 1) = B * in.c2;
    r(0, 2) = -(B * in.s2);
    r(1, 1) = r11 * in.c2 + r12 * in.s2;
    r(1, 2) = r12 * in.c2 - r11 * in.s2;
    r(2, 1) = r21 * in.c2 + r22 * in.s2;
    r(2, 2) = r22 * in.c2 - r21 * in.s2;
    r(3, 1) = D * in.s2;
    r(3, 2) = D * in.c2;
    return r;
}

}  // namespace iris::mueller
