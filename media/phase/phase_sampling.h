// The one step every rotationally symmetric phase function shares: a direction wi whose
// scattering-angle cosine cos θ = −wo·wi (phase_function.h) is the given value, at azimuth 2πu
// around the forward direction −wo.
#pragma once

#include "core/frame.h"
#include "core/math.h"

namespace iris {

inline vec3 directionWithScatteringCosine(const vec3& wo, float cosTheta, float u) {
    cosTheta = std::clamp(cosTheta, -1.0f, 1.0f);
    const float sinTheta = std::sqrt(std::max(0.0f, 1.0f - cosTheta * cosTheta));
    const float phi = 2.0f * kPi * u;
    return Frame::fromNormal(-wo).toWorld(vec3(sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta));
}

}  // namespace iris
