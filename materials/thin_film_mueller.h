// A thin-film coating's Mueller matrices in a BSDF's local frame (polarized mode,
// docs/polarization.md): per wavelength, the stack's powers and cross terms
// (ThinFilmCoating::polarization, from its complex s and p amplitudes) in the interface layout of
// spectral/mueller.h, at the (micro)surface normal m, for light arriving along −wi and leaving along
// wo, put into the bases BSDF::evalMueller uses (materials/mueller_frames.h fromSAxisBases).
#pragma once

#include "materials/thin_film_coating.h"
#include "spectral/mueller.h"

namespace iris {

/// Reflection, the stack lit at cosθ from the exterior (below = false) or the substrate.
MuellerSpectrum coatingReflectionMueller(const ThinFilmCoating& c, float cosTheta, bool below, const vec3& m, const vec3& wi,
                                         const vec3& wo);
/// Transmission through the stack, lit at cosθ from the exterior or the substrate side.
MuellerSpectrum coatingTransmissionMueller(const ThinFilmCoating& c, float cosTheta, bool below, const vec3& m, const vec3& wi,
                                           const vec3& wo);
/// A depolarizing base under the coating (iridescent_diffuse; the model of Mitsuba 3's pplastic):
/// in through the stack at cos θi, depolarized with the factor `base` per wavelength, out at
/// cos θo: base · T_out[:, 0] T_in[0, :], whose (0, 0) entry is base · T(θi) T(θo).
MuellerSpectrum coatingDiffuseMueller(const ThinFilmCoating& c, const SampledSpectrum& base, const vec3& wi, const vec3& wo);

}  // namespace iris
