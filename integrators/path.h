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
    /// Mitsuba 0.6's strictNormals: follow (and light) only directions whose geometric and shading
    /// sides agree (integrators/transport_steps.h, sidesAgree).
    bool strictNormals = false;
};

/// Reads max_depth, rr_depth, hide_emitters and strict_normals (Mitsuba 0.6: maxDepth, rrDepth,
/// hideEmitters, strictNormals); shared by path, direct, volpath and volpathmis.
PathParams readPathParams(const Properties& p);

class PathIntegrator final : public Integrator {
public:
    /// `maxDepth`, `rrDepth`: the values the paths use (for `direct`: 2 and never).
    PathIntegrator(std::string type, const PathParams& params, int maxDepth, int rrDepth);
    SampledSpectrum Li(const Scene& scene, const Ray& ray, SampledWavelengths& wl, Sampler& sampler, Arena& arena,
                       PathStats& stats) const override;
    const PathParams& params() const { return params_; }
    /// The polarized form (integrators/path_polarized.cpp, docs/polarization.md).
    bool hasPolarizedForm() const override { return true; }
    void LiStokes(const Scene& scene, const Ray& ray, SampledWavelengths& wl, Sampler& sampler, Arena& arena, PathStats& stats,
                  StokesEstimate& est) const override;

private:
    /// Next-event estimation at si with MIS (power heuristic): one light sample, its occlusion test.
    SampledSpectrum directLight(const Scene& scene, const SurfaceInteraction& si, const Frame& frame, const BSDF& bsdf,
                                const vec3& wo, const vec2& uL, const SampledWavelengths& wl,
                                const SampledSpectrum& beta, PathStats& stats) const;

    PathParams params_;
    int maxDepth_, rrDepth_;
    bool hideEmitters_;
};

}  // namespace iris
