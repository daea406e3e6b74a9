// Unidirectional path tracing with next-event estimation and multiple importance sampling
// (Veach 1997 ch. 9; pbrt-v4 §13.4), Russian roulette, and Mitsuba's max_depth convention: a path
// of max_depth segments at most (1 = directly visible emitters only, 2 = direct illumination,
// −1 = unlimited). The `direct` integrator is this with max_depth = 2 and no Russian roulette.
#pragma once

#include "render/integrator.h"

namespace iris {

class PathIntegrator final : public Integrator {
public:
    PathIntegrator(const Scene& scene, int maxDepth, int rrDepth, bool hideEmitters);
    SampledSpectrum Li(const Ray& ray, SampledWavelengths& wl, Sampler& sampler, Arena& arena,
                       PathStats& stats) const override;

private:
    const Scene& scene_;
    int maxDepth_, rrDepth_;
    bool hideEmitters_;
};

}  // namespace iris
