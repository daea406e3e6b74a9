// Rays that leave lights at infinity (environment and directional lights) for light tracing and
// BDPT: their origins lie on a disk that covers the scene, perpendicular to the direction of travel
// (pbrt-v4 §12.5 UniformInfiniteLight::SampleLe and DistantLight::SampleLe).
#pragma once

#include "render/lights/light.h"

namespace iris {

/// A point of the disk of radius bounds.radius perpendicular to wi, centred bounds.radius · wi
/// beyond the scene's centre (wi points towards the light): a ray from it along −wi crosses the
/// whole scene. Uniform in area, density emissionDiskPdf(bounds).
vec3 emissionDiskOrigin(const SceneBounds& bounds, const vec3& wi, const vec2& u);
/// 1 / (π R²), the area density of emissionDiskOrigin.
float emissionDiskPdf(const SceneBounds& bounds);

}  // namespace iris
