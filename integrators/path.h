// Unidirectional path tracing with next-event estimation and multiple importance sampling
// (Veach 1997 ch. 9; pbrt-v4 §13.4), Russian roulette, and Mitsuba's max_depth convention: a path
// of max_depth segments at most (1 = directly visible emitters only, 2 = direct illumination,
// −1 = unlimited). The `direct` integrator is this with max_depth = 2 and no Russian roulette.
#pragma once

#include "render/integrator.h"

namespace iris {

/// The parameters as the scene gave them.
struct PathParams {
    int maxDepth = -1;  // −1: unlimited (Russian roulette terminates)
    int rrDepth = 5;    // Russian roulette starts after this many segments
    bool hideEmitters = false;
};

/// Reads max_depth, rr_depth and hide_emitters (Mitsuba 0.6: maxDepth, rrDepth, hideEmitters)
/// and strict_normals (accepted, no effect); shared by path, direct, volpath and volpathmis.
PathParams readPathParams(const Properties& p);

class PathIntegrator final : public Integrator {
public:
    /// `maxDepth`, `rrDepth`: the values the paths use (for `direct`: 2 and never).
    PathIntegrator(std::string type, const PathParams& params, int maxDepth, int rrDepth);
    SampledSpectrum Li(const Scene& scene, const Ray& ray, SampledWavelengths& wl, Sampler& sampler, Arena& arena,
                       PathStats& stats) const override;
    const PathParams& params() const { return params_; }

private:
    PathParams params_;
    int maxDepth_, rrDepth_;
    bool hideEmitters_;
};

}  // namespace iris
