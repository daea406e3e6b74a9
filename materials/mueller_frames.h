// Where the Mueller matrices of BSDFs live (polarized mode, docs/polarization.md): every
// BSDF::evalMueller returns its matrix from stokesBasis(−wi) to stokesBasis(wo), local frame. The
// helpers here put a matrix known in other bases there:
//   - specular interfaces (smooth or a microfacet) are known in s-axis bases, the axis normal to
//     the plane of incidence (Mitsuba 3 conductor.cpp, roughconductor.cpp, dielectric.cpp: the s
//     axes m × (−ŵ_light) and m × ŵ_out, rotated to the implicit bases);
//   - wrappers (normalmap, bumpmap, twosided) evaluate a nested BSDF in another local frame.
#pragma once

#include "core/frame.h"
#include "spectral/mueller.h"

namespace iris {

/// M known in the s-axis bases of the (micro)surface normal m, for light arriving along −wi and
/// leaving along wo (unit, local frame): the in axis normalize(m × (−wi)), the out axis
/// normalize(m × wo), both (1, 0, 0) when the in axis vanishes (incidence along m), re-expressed
/// from stokesBasis(−wi) to stokesBasis(wo) (Mitsuba 3 rotate_mueller_basis as its pBSDFs call it).
MuellerSpectrum fromSAxisBases(const MuellerSpectrum& m, const vec3& normal, const vec3& wi, const vec3& wo);

/// A nested BSDF's matrix `nested`, computed in a local frame whose axes are `f` (s, t, n given in
/// this frame's coordinates; f.toWorld maps nested-local to local), re-expressed for the directions
/// wi, wo of this frame. `mirrored`: f is an improper map (a mirror, as twosided's z → −z), which
/// reverses the handedness of the Stokes frames: S2 and S3 change sign on both sides,
/// Q M Q with Q = diag(1, 1, −1, −1) (Collett ch. 5: a mirror reverses the sense of rotation).
MuellerSpectrum fromNestedFrame(const MuellerSpectrum& nested, const Frame& f, bool mirrored, const vec3& wi, const vec3& wo);

}  // namespace iris
