#include "spectral/mueller.h"

#include "spectral/spectrum_lanes.h"

namespace iris::mueller {

using lanes::Float4;
using lanes::loadGroup;
using lanes::storeGroup;

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
    // One group of four lanes at a time (spectral/lanes.h: no temporaries, no scalar stores read
    // back as vectors; this runs at every polarized vertex with a dense matrix), the same float
    // operations in the same order as the spectrum arithmetic they replace, so the same values.
    // Every entry of r is written: it needs no copy of m.
    MuellerSpectrum r(m.size());
    const Float4 oc = lanes::broadcast(out.c2), os = lanes::broadcast(out.s2);
    const Float4 ic = lanes::broadcast(in.c2), is = lanes::broadcast(in.s2);
    for (int l = 0; l < SampledSpectrum::paddedSize(m.size()); l += SampledSpectrum::kLanes) {
        Float4 x[4][4];
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j) x[i][j] = loadGroup(m(i, j), l);
        for (int j = 0; j < 4; ++j) {  // R_out · M: rows 1 and 2 (rotator rows [c, s], [−s, c]; Collett ch. 5 eq. 43)
            const Float4 a = x[1][j], b = x[2][j];
            x[1][j] = a * oc + b * os;
            x[2][j] = b * oc - a * os;
        }
        for (int i = 0; i < 4; ++i) {  // (R_out M) · R_inᵀ: columns 1 and 2
            const Float4 a = x[i][1], b = x[i][2];
            x[i][1] = a * ic + b * is;
            x[i][2] = b * ic - a * is;
        }
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j) storeGroup(r(i, j), l, x[i][j]);
    }
    return r;
}

MuellerSpectrum rotatedInterface(const MuellerSpectrum& m, const BasisRotation& in, const BasisRotation& out) {
    // rotateBasesDense's operations on [[A, B, 0, 0], [B, A, 0, 0], [0, 0, C, −D], [0, 0, D, C]]
    // without the products with its zeros (x·c + 0·s = x·c), in the same order and float lane by
    // lane (four lanes at a time), so that every entry has the dense product's value (up to the sign
    // of a zero). Rows 0 and 3 of R_out M are M's, and (0, 0), (0, 3), (3, 0), (3, 3) stay M's
    // (A, 0, 0, C).
    MuellerSpectrum r(m.size());
    const Float4 oc = lanes::broadcast(out.c2), os = lanes::broadcast(out.s2);
    const Float4 ic = lanes::broadcast(in.c2), is = lanes::broadcast(in.s2);
    auto put = [&r](int i, int j, int l, Float4 v) { storeGroup(r(i, j), l, v); };
    for (int l = 0; l < SampledSpectrum::paddedSize(m.size()); l += SampledSpectrum::kLanes) {
        const Float4 A = loadGroup(m(0, 0), l), B = loadGroup(m(0, 1), l);
        const Float4 C = loadGroup(m(2, 2), l), mD = loadGroup(m(2, 3), l);
        const Float4 D = loadGroup(m(3, 2), l);
        put(0, 0, l, A), put(0, 3, l, loadGroup(m(0, 3), l));
        put(3, 0, l, loadGroup(m(3, 0), l)), put(3, 3, l, loadGroup(m(3, 3), l));
        // R_out · M: rows 1 and 2 become (a c + b s, b c − a s) of their old values (Collett ch. 5 eq. 43).
        const Float4 a1 = A * oc, c1 = C * os, a2 = -(A * os), c2 = C * oc;
        put(1, 0, l, B * oc), put(2, 0, l, -(B * os)), put(1, 3, l, mD * os), put(2, 3, l, mD * oc);
        // (R_out M) · R_inᵀ: columns 1 and 2 become (a c + b s, b c − a s) of their old values.
        put(0, 1, l, B * ic), put(0, 2, l, -(B * is));
        put(1, 1, l, a1 * ic + c1 * is), put(1, 2, l, c1 * ic - a1 * is);
        put(2, 1, l, a2 * ic + c2 * is), put(2, 2, l, c2 * ic - a2 * is);
        put(3, 1, l, D * is), put(3, 2, l, D * ic);
    }
    return r;
}

}  // namespace iris::mueller
