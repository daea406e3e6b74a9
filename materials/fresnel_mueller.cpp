#include "materials/fresnel_mueller.h"

#include "materials/fresnel_polarized.h"
#include "materials/mueller_frames.h"

namespace iris {

MuellerSpectrum fresnelReflectionMueller(const vec3& m, const vec3& wi, const vec3& wo, const SampledSpectrum& eta,
                                         const SampledSpectrum* k) {
    const float c = glm::dot(wi, m);
    const MuellerSpectrum M = interfaceMuellerPerLane(eta.size(), [&](int i) { return reflectionTerms(c, eta[i], k ? (*k)[i] : 0.0f); });
    return fromSAxisBases(M, m, wi, wo);
}

MuellerSpectrum fresnelTransmissionMueller(const vec3& m, const vec3& wi, const vec3& wo, const SampledSpectrum& eta) {
    const float c = glm::dot(wi, m);
    const MuellerSpectrum M = interfaceMuellerPerLane(eta.size(), [&](int i) { return transmissionTerms(c, eta[i]); });
    return fromSAxisBases(M, m, wi, wo);
}

}  // namespace iris
