// The SGGX microflake distribution (Heitz, Dupuy, Crassin & Dachsbacher 2015, "The SGGX
// microflake distribution", ACM TOG 34(4), and its supplemental material, cited "supp."): the
// microflakes are the normals of an ellipsoid given by a symmetric positive definite matrix S.
// In double precision: thin fibres (one eigenvalue of S near 0) make D and σ span many orders of
// magnitude.
#pragma once

#include <cmath>

#include "core/frame.h"
#include "core/math.h"
#include "core/sampling.h"

namespace iris {

/// A symmetric 3×3 matrix by its six entries, in Mitsuba 3's order (src/phase/sggx.cpp,
/// include/mitsuba/render/microflake.h): S_xx, S_yy, S_zz, S_xy, S_xz, S_yz.
struct SggxMatrix {
    double xx = 1, yy = 1, zz = 1, xy = 0, xz = 0, yz = 0;

    static SggxMatrix fromChannels(const float* c) { return {c[0], c[1], c[2], c[3], c[4], c[5]}; }
    /// wᵀ S w.
    double quadratic(const dvec3& w) const {
        return w.x * w.x * xx + w.y * w.y * yy + w.z * w.z * zz + 2 * (w.x * w.y * xy + w.x * w.z * xz + w.y * w.z * yz);
    }
    double det() const { return xx * (yy * zz - yz * yz) - xy * (xy * zz - yz * xz) + xz * (xy * yz - yy * xz); }
    /// wᵀ adj(S) w, where adj(S) = det(S) S⁻¹ (the cofactor matrix of the symmetric S).
    double adjugateQuadratic(const dvec3& w) const {
        return w.x * w.x * (yy * zz - yz * yz) + w.y * w.y * (xx * zz - xz * xz) + w.z * w.z * (xx * yy - xy * xy) +
               2 * (w.x * w.y * (xz * yz - zz * xy) + w.x * w.z * (xy * yz - yy * xz) + w.y * w.z * (xy * xz - xx * yz));
    }
    /// Sylvester's criterion: every leading principal minor positive.
    bool positiveDefinite() const { return xx > 0 && xx * yy - xy * xy > 0 && det() > 0; }
    /// S in the frame f: entry (a, b) is f_aᵀ S f_b with the axes (s, t, n).
    double entry(const dvec3& a, const dvec3& b) const {
        return a.x * (xx * b.x + xy * b.y + xz * b.z) + a.y * (xy * b.x + yy * b.y + yz * b.z) +
               a.z * (xz * b.x + yz * b.y + zz * b.z);
    }
};

/// σ(ω) = sqrt(ωᵀ S ω): the microflakes' projected area seen from the unit direction ω (supp. §1.3).
inline double sggxProjectedArea(const SggxMatrix& S, const dvec3& w) { return std::sqrt(std::max(0.0, S.quadratic(w))); }

/// D(m) = 1 / (π sqrt(|S|) (mᵀ S⁻¹ m)²) for the unit normal m (supp. §1.4), written with the
/// adjugate as |S|^{3/2} / (π (mᵀ adj(S) m)²); normalised so that ∫ ⟨ω, m⟩ D(m) dm = σ(ω).
inline double sggxD(const SggxMatrix& S, const dvec3& m) {
    const double d = S.det(), q = S.adjugateQuadratic(m);
    if (!(d > 0) || !(q > 0)) return 0.0;
    return d * std::sqrt(d) / (kPi * q * q);
}

/// A unit normal m distributed as the visible normals ⟨wi, m⟩ D(m) / σ(wi) seen from the unit
/// direction wi (supp. §1.5–1.6, §2.3): in the frame (ω_k, ω_j, ω_i = wi), the ellipsoid's visible
/// projected area is the image of a cosine-weighted hemisphere under the matrix of columns M_k, M_j,
/// M_i built from S expressed in that frame.
inline dvec3 sggxSampleVisibleNormal(const SggxMatrix& S, const vec3& wi, const vec2& u) {
    const Frame f = Frame::fromNormal(wi);
    const dvec3 k(f.s), j(f.t), i(f.n);
    const double sii = S.entry(i, i), sjj = S.entry(j, j), sij = S.entry(i, j), sik = S.entry(i, k), skj = S.entry(k, j);
    const double rsii = 1.0 / std::sqrt(sii), tmp = std::sqrt(std::max(0.0, sjj * sii - sij * sij));
    const dvec3 mk(std::sqrt(std::abs(S.det())) / tmp, 0.0, 0.0);
    const dvec3 mj(-rsii * (sik * sij - skj * sii) / tmp, rsii * tmp, 0.0);
    const dvec3 mi = rsii * dvec3(sik, sij, sii);
    const dvec3 h(sampleCosineHemisphere(u));
    const dvec3 local = glm::normalize(h.x * mk + h.y * mj + h.z * mi);
    return glm::normalize(local.x * k + local.y * j + local.z * i);
}

}  // namespace iris
