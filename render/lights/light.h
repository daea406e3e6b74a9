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
    vec2 uv{0.0f};          // the light surface's uv there (area lights), the map's (u, v) (environment map)
    bool infinite = false;  // shadow ray goes to infinity
    bool radianceDeferred = false;  // L not looked up yet (Light::sampleLiDeferred): Light::deferredRadiance gives it
};

/// A ray leaving a light (light tracing and BDPT, pbrt-v4 §12.1 Light::SampleLe, Veach 1997
/// §10.2): its origin and unit direction, what it carries, and the two densities it was drawn with.
struct LightEmission {
    Ray ray;               // from a surface, its origin is offset off it (at.p is the point itself)
    /// Radiance (area and infinite lights), radiant intensity (point, spot, projector) or
    /// irradiance (directional) leaving along ray.d.
    SampledSpectrum L;
    vec3 n{0.0f};          // the surface normal at the origin (area lights), 0 otherwise
    TextureQuery at;       // the origin as the light's radiance texture sees it (area lights)
    float pdfPos = 0.0f;   // area density of the origin (1 for a delta position)
    float pdfDir = 0.0f;   // solid-angle density of the direction (1 for a delta direction)
    /// The path throughput the ray starts with, L |cos θ| / (pdfPos pdfDir) (pbrt-v4
    /// GenerateLightSubpath); |cos θ| only for origins on a surface.
    SampledSpectrum weight() const {
        const float cosTheta = glm::dot(n, n) > 0 ? std::abs(glm::dot(n, ray.d)) : 1.0f;
        return L * (cosTheta / (pdfPos * pdfDir));
    }
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
    /// sampleLi's sample (the same direction, pdf and shadow-ray target from the same u) whose
    /// radiance a light with a costly lookup may leave out (radianceDeferred, L empty), for a caller
    /// that needs it only when the sample contributes: next-event estimation after the BSDF and the
    /// shadow ray. The default is sampleLi.
    virtual std::optional<LightSample> sampleLiDeferred(const vec3& p, const vec2& u, const SampledWavelengths& wl) const {
        return sampleLi(p, u, wl);
    }
    /// The radiance sampleLi gives for a sample of sampleLiDeferred (ls.L when it was not deferred).
    virtual SampledSpectrum deferredRadiance(const LightSample& ls, const SampledWavelengths&) const { return ls.L; }

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

    /// A ray leaving the light: uPos draws its origin, uDir its direction; `bounds` are the
    /// scene's (infinite and directional lights start their rays on a disk that covers it). The
    /// default serves infinite lights from sampleLi and pdfLi (render/lights/light_emission.cpp);
    /// every other type overrides it. nullopt when nothing leaves.
    virtual std::optional<LightEmission> sampleLe(const vec2& uPos, const vec2& uDir, const SampledWavelengths& wl,
                                                  const SceneBounds& bounds) const;
    /// The densities sampleLe has for a ray leaving point p (normal n for area lights, else 0) in
    /// direction w, as {pdfPos, pdfDir}; for infinite lights w is the ray's direction into the
    /// scene and p is unused.
    virtual vec2 pdfLe(const vec3& p, const vec3& n, const vec3& w, const SceneBounds& bounds) const;
};

using LightPtr = std::shared_ptr<Light>;
/// Emitter types by scene-file name (`<emitter type="...">`; area emitters are attached to shapes).
using LightRegistry = Registry<Light>;

}  // namespace iris
