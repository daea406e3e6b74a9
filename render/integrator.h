// Light transport algorithms. An integrator estimates the radiance arriving along a camera ray at
// the path's wavelengths.
#pragma once

#include <memory>

#include "core/arena.h"
#include "core/rng.h"
#include "render/scene.h"

namespace iris {

/// Counters a render thread accumulates (summed by the renderer).
struct PathStats {
    uint64_t rays = 0;         // closest-hit and shadow rays traced
    uint64_t paths = 0;
};

class Integrator {
public:
    virtual ~Integrator() = default;
    virtual SampledSpectrum Li(const Ray& ray, SampledWavelengths& wl, Sampler& sampler, Arena& arena,
                               PathStats& stats) const = 0;

    /// "path" or "direct"; throws iris::Error for unknown types.
    static std::unique_ptr<Integrator> create(const IntegratorDescription& desc, const Scene& scene);
};

}  // namespace iris
