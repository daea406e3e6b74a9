// The multiple-importance weight of one BDPT connection strategy (Veach 1997 §10.3, eqs. 10.9–10.10
// and the power heuristic eq. 9.13; pbrt-v4 §13.x MISWeight): the path of s light and t camera
// vertices could have been sampled by every other split (s', t') with s' + t' = s + t; the weight is
// p_s^β / Σ p_i^β, computed from the ratios p_{i±1} / p_i of the vertices' forward and reverse
// densities, β = 2 (power) or 1 (balance). Delta vertices cannot be connected: a split at one is
// not counted (and their zero densities count as 1, pbrt-v4 remap0).
#pragma once

#include "integrators/bdpt_vertex.h"

namespace iris {

enum class MISHeuristic { Power, Balance };

/// Which splits a render uses besides the random walks: Mitsuba 0.6's bdpt can leave out the
/// connections to the camera (lightImage) and the sampled light points (sampleDirect); their weight
/// then goes to the others.
struct StrategySet {
    bool lightImage = true;    // t = 1
    bool sampleDirect = true;  // s = 1
};

/// The weight of strategy (s, t). `sampled` is the vertex the strategy sampled itself (the light
/// point for s = 1, the camera point for t = 1) in place of light[0] or camera[0].
float misWeight(const Scene& scene, const BDPTVertex* light, const BDPTVertex* camera, const BDPTVertex& sampled, int s, int t,
                MISHeuristic h, const StrategySet& strategies);

}  // namespace iris
