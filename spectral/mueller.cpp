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

}  // namespace iris::mueller
