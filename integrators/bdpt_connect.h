// The connection strategies of BDPT (Veach 1997 §10.2.1; pbrt-v4 §13.x ConnectBDPT): a path of s
// light-subpath and t camera-subpath vertices is completed by
//   s = 0   the camera subpath ends on an emitter:        β_t Le
//   t = 1   the light subpath's vertex seen by the camera: β_s f*(q, camera) |cos| C W  (splatted)
//   s = 1   a light point sampled from the camera vertex: β_t f |cos| Le / p   (next-event estimation)
//   else    the two end vertices joined:                  β_s f* C G f β_t
// with f* the adjoint BSDF, C Veach's shading-normal correction of the light vertex (eq. 5.19) and
// G = |cos_s| |cos_t| / d² the geometry term with the shading normals; every connection is tested
// for visibility (any surface blocks it: BDPT samples pass-through lobes as vertices of their own).
#pragma once

#include <optional>

#include "integrators/bdpt_mis.h"
#include "render/integrator.h"

namespace iris {

struct BDPTConnection {
    SampledSpectrum L;              // the strategy's contribution, before its MIS weight
    BDPTVertex sampled;             // the vertex the strategy sampled (s = 1, t = 1)
    std::optional<vec2> filmPos;    // t = 1: where it lands on the film
};

/// The contribution of strategy (s, t); nullopt where it gives nothing. s = 1 draws a 1D and a 2D
/// sample for the light point.
std::optional<BDPTConnection> connectStrategy(const Scene& scene, const BDPTVertex* light, const BDPTVertex* camera, int s, int t,
                                              const SampledWavelengths& wl, Sampler& sampler, bool strictNormals, PathStats& stats);

}  // namespace iris
