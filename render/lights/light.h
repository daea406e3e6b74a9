// Light sources. Every light can be sampled from a reference point (next-event estimation) and
// report the solid-angle density of that strategy (for multiple importance sampling).
// Radiance is in the relative units of docs/conventions.md.
#pragma once

#include <memory>
#include <optional>

#include "core/ray.h"
#include "core/registry.h"
#include "materials/textures/texture.h"
#include "spectral/sampled_spectrum.h"
#include "spectral/wavelengths.h"

namespace iris {

struct SceneBounds {
    vec3 center{0.0f};
    float radius = 1.0f;
};

struct LightSample {
    SampledSpectrum L;      // radiance arriving at the reference point (before visibility)
    vec3 wi{0.0f};          // direction from the reference point to the light
    float pdf = 0.0f;       // solid-angle density (or 1 for delta lights)
    vec3 pLight{0.0f};      // point on the light (for the shadow ray)
    vec3 nLight{0.0f};      // light surface normal (area lights), for the shadow ray's end offset
    vec2 uv{0.0f};          // the light surface's uv there (area lights)
    bool infinite = false;  // shadow ray goes to infinity
};

class Light {
public:
    enum class Type { DeltaPosition, DeltaDirection, Area, Infinite };

    virtual ~Light() = default;
    virtual Type type() const = 0;
    bool isDelta() const { return type() == Type::DeltaPosition || type() == Type::DeltaDirection; }

    /// Called once the scene bounds are known (directional and environment lights need them).
    virtual void preprocess(const SceneBounds&) {}

    /// Sample incident radiance at point p.
    virtual std::optional<LightSample> sampleLi(const vec3& p, const vec2& u, const SampledWavelengths& wl) const = 0;

    /// Solid-angle density with which sampleLi would produce direction wi from p. For area lights
    /// `hit` is the intersection with this light along wi from p (found by a ray that may have
    /// started elsewhere on that line, e.g. after a pass-through surface); for infinite lights hit
    /// is unused.
    virtual float pdfLi(const vec3& p, const vec3& wi, const SurfaceInteraction* hit) const { return 0.0f; }

    /// Emitted radiance: area lights at a surface point (`at`: position, uv and, on meshes, the
    /// triangle and barycentrics a radiance texture looks up; normal n) towards w; infinite lights
    /// for a ray leaving the scene in direction w (at and n unused).
    virtual SampledSpectrum Le(const TextureQuery& at, const vec3& n, const vec3& w, const SampledWavelengths& wl) const {
        return SampledSpectrum(wl.size());
    }
};

using LightPtr = std::shared_ptr<Light>;
/// Emitter types by scene-file name (`<emitter type="...">`; area emitters are attached to shapes).
using LightRegistry = Registry<Light>;

}  // namespace iris
