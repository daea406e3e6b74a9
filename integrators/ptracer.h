// Particle tracing (Mitsuba 3's `ptracer`, src/integrators/ptracer.cpp; Veach 1997 §10.2 "light
// tracing"; pbrt-v4's light-path integrator): paths start at the lights and every vertex with a
// non-delta BSDF is connected to the sensor, its contribution splatted where it lands on the film
// (render/splat_film.h). One light path per pixel sample: a pass of W × H light paths, each splat
// scaled by 1/(W H). Directly visible emitters (unless hide_emitters) are sampled on the emitter and
// connected to the sensor, as Mitsuba 3 does (sample_visible_emitters), except infinite lights,
// whose directions are drawn from the sensor's view (see splatVisibleInfinite); delta lights cannot
// be seen.
//
// Differences from Mitsuba 3, each for agreement with iris's `path`: the connection to the sensor
// crosses pass-through surfaces (mask, null, thindielectric) with their weight, and counts each as a
// segment against max_depth (Mitsuba 3's ray_test stops there, so its ptracer renders what lies
// behind a mask black); directions whose geometric and shading sides disagree are kept unless
// strict_normals is set (as `path`; Mitsuba 3's ptracer always drops them); Russian roulette acts on
// the throughput relative to the path's start (Mitsuba 3 uses the absolute one, which makes survival
// depend on the light's units). None of these changes the expectation where both are defined.
//
// What light tracing cannot render: a path whose vertex next to the sensor has only delta lobes (a
// smooth mirror or glass seen by the camera, the specular coat of `plastic`) cannot be connected
// to the sensor; those parts of the image are black (as in Mitsuba 3 and pbrt-v4). Media are not
// handled (Mitsuba 3's ptracer neither); the loader refuses scenes with media.
#pragma once

#include "integrators/path.h"

namespace iris {

class SplatFilm;

class PTracerIntegrator final : public Integrator {
public:
    /// `samplesPerPass` is Mitsuba 3's scheduling parameter: accepted and recorded; iris's passes
    /// are always one light path per pixel (the image's expectation does not depend on it).
    PTracerIntegrator(const PathParams& params, int samplesPerPass);
    SampledSpectrum Li(const Scene& scene, const Ray& ray, SampledWavelengths& wl, Sampler& sampler, Arena& arena,
                       PathStats& stats) const override;
    bool splats() const override { return true; }
    SampledSpectrum sample(const Scene& scene, const Ray& ray, SampledWavelengths& wl, Sampler& sampler, Arena& arena,
                           PathStats& stats, SplatFilm& splats) const override;
    /// For tests only: without Veach's shading-normal correction (a deliberately wrong estimator).
    void disableShadingCorrection() { shadingCorrection_ = false; }

private:
    void splatVisibleEmitter(const Scene& scene, SampledWavelengths& wl, Sampler& sampler, Arena& arena, PathStats& stats,
                             SplatFilm& splats) const;
    void splatVisibleInfinite(const Scene& scene, const Light& light, float pmf, const vec2& u, SampledWavelengths& wl, Arena& arena,
                              PathStats& stats, SplatFilm& splats) const;
    void traceLightPath(const Scene& scene, SampledWavelengths& wl, Sampler& sampler, Arena& arena, PathStats& stats,
                        SplatFilm& splats) const;

    PathParams params_;
    int maxDepth_, samplesPerPass_;
    bool shadingCorrection_ = true;
};

}  // namespace iris
