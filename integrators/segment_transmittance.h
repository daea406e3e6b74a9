// What lies between two points of a connection (light tracing's connections to the sensor, BDPT's
// connections): nothing, a blocking surface, or pass-through surfaces (mask, null, thindielectric)
// that let the segment through with their weight (BSDF::nullTransmission).
#pragma once

#include <optional>
#include <utility>

#include "core/arena.h"
#include "render/integrator.h"

namespace iris {

/// The weight of the segment from p (offset off its surface along ng when ng ≠ 0) to q, and the
/// number of surfaces crossed, nullopt when a surface blocks it. With `passThrough` the segment
/// crosses surfaces that have a pass-through lobe with that lobe's weight, each crossing a segment
/// of the path as `path` counts it (ptracer); without it every surface blocks (BDPT, whose subpaths
/// sample those lobes as vertices of their own).
std::optional<std::pair<SampledSpectrum, int>> segmentTransmittance(const Scene& scene, const vec3& p, const vec3& ng, const vec3& q,
                                                                     const SampledWavelengths& wl, bool passThrough, Arena& arena,
                                                                     PathStats& stats);

}  // namespace iris
