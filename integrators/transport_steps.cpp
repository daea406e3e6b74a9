#include "integrators/transport_steps.h"

#include <algorithm>

namespace iris {

LightChoice chooseLight(const Scene& scene, float u) {
    const auto& lights = scene.lights();
    if (lights.empty()) return {};
    const float n = float(lights.size());
    const int i = std::min(int(u * n), int(lights.size()) - 1);
    const float reused = std::min(kOneMinusEpsilon, std::max(0.0f, u * n - float(i)));
    return {lights[size_t(i)].get(), lightChoicePmf(scene), reused};
}

float lightSamplingPdf(const Scene& scene, const Light& light, const vec3& from, const vec3& d, const SurfaceInteraction* hit) {
    const float pmf = lightChoicePmf(scene);
    return pmf * light.pdfLi(from, d, hit);
}

std::optional<VertexLightSample> sampleChosenLight(const Scene& scene, const vec3& p, const vec2& uL, const SampledWavelengths& wl,
                                                   RadianceLookup lookup) {
    const LightChoice choice = chooseLight(scene, uL.x);
    if (!choice.light) return std::nullopt;
    const vec2 u(choice.uReused, uL.y);
    const std::optional<LightSample> ls =
        lookup == RadianceLookup::Deferred ? choice.light->sampleLiDeferred(p, u, wl) : choice.light->sampleLi(p, u, wl);
    if (!ls || !(ls->pdf > 0) || (!ls->radianceDeferred && ls->L.isBlack())) return std::nullopt;
    VertexLightSample s;
    s.light = choice.light;
    s.ls = *ls;
    s.lightPdf = choice.pmf * ls->pdf;
    return s;
}

bool resolveRadiance(VertexLightSample& s, const SampledWavelengths& wl) {
    if (s.ls.radianceDeferred) {
        s.ls.L = s.light->deferredRadiance(s.ls, wl);
        s.ls.radianceDeferred = false;
    }
    return !s.ls.L.isBlack();
}

std::optional<VertexLightSample> sampleLightAtSurface(const Scene& scene, const vec3& p, const vec3& ng, const Frame& frame,
                                                      const BSDF& bsdf, const vec3& wo, const vec2& uL,
                                                      const SampledWavelengths& wl, bool strictNormals, RadianceLookup lookup) {
    std::optional<VertexLightSample> s = sampleChosenLight(scene, p, uL, wl, lookup);
    if (!s) return std::nullopt;
    const vec3 wi = frame.toLocal(s->ls.wi);
    if (strictNormals && !sidesAgree(s->ls.wi, ng, wi.z)) return std::nullopt;
    s->f = bsdf.eval(wo, wi, TransportMode::Radiance);
    if (s->f.isBlack()) return std::nullopt;
    s->f *= std::abs(wi.z);
    s->scatterPdf = bsdf.pdf(wo, wi, TransportMode::Radiance);
    return s;
}

std::optional<VertexLightSample> sampleLightInMedium(const Scene& scene, const vec3& p, const PhaseFunction& phase, const vec3& wo,
                                                     const vec2& uL, const SampledWavelengths& wl) {
    std::optional<VertexLightSample> s = sampleChosenLight(scene, p, uL, wl);
    if (!s) return std::nullopt;
    s->scatterPdf = phase.pdf(p, wo, s->ls.wi);
    s->f = SampledSpectrum(wl.size(), phase.eval(p, wo, s->ls.wi));
    if (s->f.isBlack()) return std::nullopt;
    return s;
}

std::optional<SampledSpectrum> crossingWeight(const SurfaceInteraction& si, const vec3& dir, const SampledWavelengths& wl,
                                              Arena& arena) {
    if (!si.material->transmitsShadowRays()) return std::nullopt;
    const ShadingPoint sp = shadingPointAt(si);
    SampledWavelengths own = wl;  // a nested dispersive BSDF may end lanes: of this query, not of the path
    const BSDF* bsdf = si.material->getBSDF(sp, own, arena);
    if (!bsdf) return SampledSpectrum(wl.size(), 1.0f);  // a boundary only
    return bsdf->nullTransmission(sp.shading.toLocal(-dir));
}

std::optional<LightPathStart> startLightPath(const Scene& scene, float uLight, const vec2& uPos, const vec2& uDir,
                                             const SampledWavelengths& wl) {
    const LightChoice choice = chooseLight(scene, uLight);
    if (!choice.light) return std::nullopt;
    const std::optional<LightEmission> e = choice.light->sampleLe(uPos, uDir, wl, scene.bounds());
    if (!e || !(e->pdfPos > 0) || !(e->pdfDir > 0) || e->L.isBlack()) return std::nullopt;
    LightPathStart s;
    s.light = choice.light;
    s.pmf = choice.pmf;
    s.emission = *e;
    s.beta = e->weight() / choice.pmf;
    return s;
}

float adjointShadingCorrection(const vec3& woWorld, const vec3& wiWorld, const vec3& ng, const vec3& ns) {
    const float den = std::abs(glm::dot(woWorld, ng) * glm::dot(wiWorld, ns));
    if (!(den > 0)) return 0.0f;
    return std::abs(glm::dot(woWorld, ns) * glm::dot(wiWorld, ng)) / den;
}

}  // namespace iris
