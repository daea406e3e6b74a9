// Light transport algorithms. An integrator estimates the radiance arriving along a camera ray at
// the path's wavelengths. Every integrator type registers a factory in IntegratorRegistry under
// its scene-file name (integrators/); it reads its parameters when the scene is loaded and is
// given the scene when it renders.
#pragma once

#include <memory>
#include <string>

#include "core/arena.h"
#include "core/registry.h"
#include "core/rng.h"
#include "render/polarized_estimate.h"
#include "render/scene.h"

namespace iris {

class SplatFilm;

/// Counters a render thread accumulates (summed by the renderer).
struct PathStats {
    uint64_t rays = 0;         // closest-hit and shadow rays traced
    uint64_t paths = 0;
};

class Integrator {
public:
    /// `type`: the scene-file name; `maxDepth`: Mitsuba's max_depth (−1 = unlimited); both are
    /// recorded in the image's metadata and in checkpoints.
    Integrator(std::string type, int maxDepth) : type_(std::move(type)), maxDepth_(maxDepth) {}
    virtual ~Integrator() = default;
    virtual SampledSpectrum Li(const Scene& scene, const Ray& ray, SampledWavelengths& wl, Sampler& sampler,
                               Arena& arena, PathStats& stats) const = 0;
    const std::string& type() const { return type_; }
    /// True for integrators that render participating media (volpath, volpathmis); the loader
    /// refuses a scene with media and an integrator that would ignore them.
    virtual bool rendersMedia() const { return false; }
    /// True for light-tracing integrators (ptracer, bdpt), which also add contributions to other
    /// film positions than the camera sample's: the renderer then keeps a SplatFilm per pass and
    /// calls sample() instead of Li() (render/splat_film.h).
    virtual bool splats() const { return false; }
    /// One camera sample of a splatting integrator: returns the estimate at the camera ray's own
    /// film position and gives the others to `splats`.
    virtual SampledSpectrum sample(const Scene& scene, const Ray& ray, SampledWavelengths& wl, Sampler& sampler, Arena& arena,
                                   PathStats& stats, SplatFilm& splats) const {
        return (void)splats, Li(scene, ray, wl, sampler, arena, stats);
    }
    int maxDepth() const { return maxDepth_; }
    /// Polarized mode (docs/polarization.md): integrators with a polarized form say so and add the
    /// Stokes estimate along the ray to est.S (est.rows rows, reference basis est.basis). The
    /// renderer refuses a polarized render with any other integrator before it starts.
    virtual bool hasPolarizedForm() const { return false; }
    virtual void LiStokes(const Scene& scene, const Ray& ray, SampledWavelengths& wl, Sampler& sampler, Arena& arena,
                          PathStats& stats, StokesEstimate& est) const;

private:
    std::string type_;
    int maxDepth_;
};

using IntegratorRegistry = Registry<Integrator>;

/// An integrator of the given type with its default parameters (for scenes built in code).
IntegratorPtr makeIntegrator(const std::string& type);

}  // namespace iris
