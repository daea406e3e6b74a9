// The reference frames of Stokes vectors (polarized mode, docs/polarization.md), as Mitsuba 3
// defines them (include/mitsuba/render/mueller.h): a Stokes vector travelling along `forward` is
// expressed in the basis vector stokesBasis(forward), never stored, recomputed where needed; a
// change of basis between two vectors orthogonal to the same direction is a rotator.
#pragma once

#include "core/frame.h"
#include "spectral/mueller.h"

namespace iris {

/// The implicit basis vector of a Stokes vector travelling along the unit vector `forward`: the
/// first tangent of the orthonormal basis around it (Mitsuba 3 mueller::stokes_basis =
/// coordinate_system(forward).first; Duff et al. 2017, "Building an Orthonormal Basis, Revisited").
inline vec3 stokesBasis(const vec3& forward) { return Frame::fromNormal(forward).s; }

/// The rotation that re-expresses a Stokes vector travelling along `forward` from the basis vector
/// `current` to `target` (both orthogonal to forward): rotator(θ) with θ the angle between them,
/// negative when forward · (current × target) < 0 (Mitsuba 3 mueller::rotate_stokes_basis, whose
/// angle is unit_angle(current, target) ∈ [0, π] also when a basis is not orthogonal to forward).
/// The cosine and sine of θ are the dot product and the signed length of the cross product, so
/// cos 2θ and sin 2θ need no trigonometry.
inline mueller::BasisRotation stokesBasisRotation(const vec3& forward, const vec3& current, const vec3& target) {
    const float c = glm::dot(current, target);
    const vec3 cr = glm::cross(current, target);
    const float s = std::copysign(glm::length(cr), glm::dot(forward, cr));
    const float n2 = c * c + s * s;
    if (!(n2 > 0)) return {};
    return {(c * c - s * s) / n2, 2.0f * c * s / n2};
}

/// M known from basis vector inCurrent (light arriving along inForward) to outCurrent (leaving along
/// outForward), re-expressed from stokesBasis(inForward) to stokesBasis(outForward): R_out M R_inᵀ
/// (Mitsuba 3 mueller::rotate_mueller_basis with the implicit bases as targets).
inline MuellerSpectrum toImplicitBases(const MuellerSpectrum& m, const vec3& inForward, const vec3& inCurrent, const vec3& outForward,
                                       const vec3& outCurrent) {
    if (m.depolarizing()) return m;
    return mueller::rotateBases(m, stokesBasisRotation(inForward, inCurrent, stokesBasis(inForward)),
                                stokesBasisRotation(outForward, outCurrent, stokesBasis(outForward)));
}

}  // namespace iris
