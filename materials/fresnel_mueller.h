// Fresnel reflection and refraction as Mueller matrices in a BSDF's local frame (polarized mode,
// docs/polarization.md): the interface terms of materials/fresnel_polarized.h at a (micro)surface
// of normal m, per wavelength, put into the bases BSDF::evalMueller uses (materials/mueller_frames.h).
// Light arrives along −wi and leaves along wo (Mitsuba 3 conductor.cpp, roughconductor.cpp,
// dielectric.cpp: wo_hat = wi here, wi_hat = wo in radiance transport).
#pragma once

#include "materials/bsdf.h"
#include "spectral/sampled_spectrum.h"

namespace iris {

/// Reflection about m with the relative index η + iκ per lane (`k` null: a dielectric, whose
/// inside is seen when wi · m < 0), the Fresnel cosine being wi · m.
MuellerSpectrum fresnelReflectionMueller(const vec3& m, const vec3& wi, const vec3& wo, const SampledSpectrum& eta,
                                         const SampledSpectrum* k = nullptr);
/// Refraction through m from wi's side into wo's, relative index η (interior / exterior) per lane.
MuellerSpectrum fresnelTransmissionMueller(const vec3& m, const vec3& wi, const vec3& wo, const SampledSpectrum& eta);

/// A sample of a delta lobe with its Mueller form: M scaled so that M(0, 0) has the sample's f
/// (M carries the lobe's Fresnel matrix; `scale` the rest of f: the lobe's weights and 1/|cos θi|).
inline std::optional<PolarizedBSDFSample> withMueller(const std::optional<BSDFSample>& s, MuellerSpectrum M,
                                                      const SampledSpectrum& scale) {
    if (!s) return std::nullopt;
    return PolarizedBSDFSample{*s, M *= scale};
}
/// A sample consistent with eval (f = eval(wo, wi)): its Mueller form is evalMueller(wo, wi).
inline std::optional<PolarizedBSDFSample> withEvalMueller(const BSDF& bsdf, const std::optional<BSDFSample>& s, const vec3& wo,
                                                          TransportMode mode) {
    if (!s) return std::nullopt;
    return PolarizedBSDFSample{*s, bsdf.evalMueller(wo, s->wi, mode)};
}

}  // namespace iris
