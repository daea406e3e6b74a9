// The two subpaths of a BDPT sample (Veach 1997 §10.2; pbrt-v4 §13.x GenerateCameraSubpath,
// GenerateLightSubpath, RandomWalk): a random walk from the camera in radiance transport and one
// from a light in importance transport (adjoint BSDFs with Veach's shading-normal correction,
// eq. 5.19), each vertex storing its forward density and its predecessor's reverse one.
#pragma once

#include "integrators/bdpt_vertex.h"
#include "render/integrator.h"

namespace iris {

struct WalkParams {
    int rrDepth = 5;             // Russian roulette from this many segments (Mitsuba 0.6 bdpt rrDepth)
    bool strictNormals = false;  // drop directions whose geometric and shading sides disagree
};

/// The camera subpath of `ray` (at most maxVertices vertices, the camera's included) in path[];
/// returns its vertex count. A ray that leaves the scene ends it with a vertex at infinity.
int cameraSubpath(const Scene& scene, const Ray& ray, SampledWavelengths& wl, Sampler& sampler, Arena& arena, PathStats& stats,
                  const WalkParams& params, BDPTVertex* path, int maxVertices);

/// A light subpath (at most maxVertices vertices, the light's included) in path[]; returns its
/// vertex count (0 when the chosen light emits nothing). Always draws the same sampler dimensions
/// before its walk.
int lightSubpath(const Scene& scene, SampledWavelengths& wl, Sampler& sampler, Arena& arena, PathStats& stats,
                 const WalkParams& params, BDPTVertex* path, int maxVertices);

}  // namespace iris
