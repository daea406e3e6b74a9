// The emission sampling every light type shares: the disk of lights at infinity and the default
// Light::sampleLe / pdfLe, which serve the infinite lights (constant, envmap) from their sampleLi
// and pdfLi (pbrt-v4 §12.5 ImageInfiniteLight::SampleLe: a direction from the light's own
// distribution, then a point on the disk).
#include "render/lights/light_emission.h"

#include "core/error.h"
#include "core/frame.h"
#include "core/sampling.h"

namespace iris {

vec3 emissionDiskOrigin(const SceneBounds& bounds, const vec3& wi, const vec2& u) {
    const Frame f = Frame::fromNormal(wi);
    const vec2 d = bounds.radius * sampleUniformDiskConcentric(u);
    return bounds.center + bounds.radius * wi + d.x * f.s + d.y * f.t;
}

float emissionDiskPdf(const SceneBounds& bounds) { return 1.0f / (kPi * bounds.radius * bounds.radius); }

std::optional<LightEmission> Light::sampleLe(const vec2& uPos, const vec2& uDir, const SampledWavelengths& wl,
                                             const SceneBounds& bounds) const {
    if (type() != Type::Infinite) fail("this emitter cannot start light paths (no sampleLe)");
    // The direction the light arrives from, as next-event estimation draws it (independent of
    // the reference point for infinite lights).
    const std::optional<LightSample> ls = sampleLi(bounds.center, uDir, wl);
    if (!ls || !(ls->pdf > 0) || ls->L.isBlack()) return std::nullopt;
    LightEmission e;
    e.ray = Ray(emissionDiskOrigin(bounds, ls->wi, uPos), -ls->wi);
    e.L = ls->L;
    e.pdfPos = emissionDiskPdf(bounds);
    e.pdfDir = ls->pdf;
    return e;
}

vec2 Light::pdfLe(const vec3& p, const vec3&, const vec3& w, const SceneBounds& bounds) const {
    if (type() != Type::Infinite) fail("this emitter cannot start light paths (no pdfLe)");
    return vec2(emissionDiskPdf(bounds), pdfLi(p, -w, nullptr));
}

}  // namespace iris
