#include "integrators/bdpt_vertex.h"

#include "integrators/transport_steps.h"
#include "render/lights/light_emission.h"

namespace iris {

bool BDPTVertex::connectible() const {
    switch (type) {
        case BDPTVertexType::Camera: return true;
        case BDPTVertexType::Light: return light && light->type() != Light::Type::DeltaDirection;
        case BDPTVertexType::Surface: return bsdf && bsdf->hasNonSpecular();
    }
    return false;
}

float BDPTVertex::absCosShading(const vec3& w) const {
    if (type == BDPTVertexType::Surface) return std::abs(glm::dot(shading.n, w));
    return onSurface() ? std::abs(glm::dot(ng, w)) : 1.0f;
}

BDPTVertex surfaceVertex(const SurfaceInteraction& si, const Frame& shading, const BSDF* bsdf, const SampledSpectrum& beta,
                         float pdf, const BDPTVertex& prev) {
    BDPTVertex v;
    v.type = BDPTVertexType::Surface;
    v.beta = beta;
    v.p = si.p;
    v.ng = si.ng;
    v.shading = shading;
    v.si = si;
    v.bsdf = bsdf;
    v.pdfFwd = convertDensity(prev, pdf, v);
    return v;
}

BDPTVertex escapedVertex(const Ray& ray, const SampledSpectrum& beta, float pdf) {
    BDPTVertex v;
    v.type = BDPTVertexType::Light;
    v.beta = beta;
    v.p = ray.o + glm::normalize(ray.d);  // a point along the direction (pbrt-v4: ray(1))
    v.infinite = true;
    v.pdfFwd = pdf;  // solid angle
    return v;
}

SampledSpectrum vertexF(const BDPTVertex& v, const BDPTVertex& next, const TransportMode mode) {
    const vec3 d = next.p - v.p;
    if (!(glm::dot(d, d) > 0) || v.type != BDPTVertexType::Surface) return SampledSpectrum(v.beta.size());
    return v.bsdf->eval(v.shading.toLocal(v.si.wo), v.shading.toLocal(glm::normalize(d)), mode);
}

float convertDensity(const BDPTVertex& from, float pdf, const BDPTVertex& to) {
    if (to.isInfiniteLight()) return pdf;
    const vec3 d = to.p - from.p;
    const float dist2 = glm::dot(d, d);
    if (!(dist2 > 0)) return 0.0f;
    if (to.onSurface()) pdf *= std::abs(glm::dot(to.ng, d)) / std::sqrt(dist2);
    return pdf / dist2;
}

float vertexPdf(const Scene& scene, const BDPTVertex& v, const BDPTVertex* prev, const BDPTVertex& next) {
    if (v.type == BDPTVertexType::Light) return lightPdf(scene, v, next);
    const vec3 dn = next.p - v.p;
    if (!(glm::dot(dn, dn) > 0)) return 0.0f;
    const vec3 wn = glm::normalize(dn);
    float pdf = 0.0f;
    if (v.type == BDPTVertexType::Camera) {
        pdf = scene.description().camera.sensor->pdfDirection(wn);
    } else {
        const vec3 dp = prev->p - v.p;
        if (!(glm::dot(dp, dp) > 0)) return 0.0f;
        pdf = v.bsdf->pdf(v.shading.toLocal(glm::normalize(dp)), v.shading.toLocal(wn), TransportMode::Radiance);
    }
    return convertDensity(v, pdf, next);
}

namespace {
const Light& emitterOf(const BDPTVertex& v) { return v.type == BDPTVertexType::Light ? *v.light : *v.si.areaLight; }
}  // namespace

float lightPdf(const Scene& scene, const BDPTVertex& v, const BDPTVertex& next) {
    const vec3 d = next.p - v.p;
    const float dist2 = glm::dot(d, d);
    if (!(dist2 > 0)) return 0.0f;
    const vec3 w = d / std::sqrt(dist2);
    float pdf;
    if (v.isInfiniteLight())
        pdf = emissionDiskPdf(scene.bounds());  // planar density of the disk the rays start on
    else
        pdf = emitterOf(v).pdfLe(v.p, v.ng, w, scene.bounds()).y / dist2;
    if (next.onSurface()) pdf *= std::abs(glm::dot(next.ng, w));
    return pdf;
}

float lightOriginPdf(const Scene& scene, const BDPTVertex& v, const BDPTVertex& next) {
    const vec3 d = next.p - v.p;
    if (!(glm::dot(d, d) > 0)) return 0.0f;
    const vec3 w = glm::normalize(d);
    // Every infinite light along −w, as the escaped ray's emission sums them.
    if (v.isInfiniteLight()) return infiniteLightDensity(scene, -w);
    return emitterOf(v).pdfLe(v.p, v.ng, w, scene.bounds()).x * lightChoicePmf(scene);
}

float infiniteLightDensity(const Scene& scene, const vec3& wi) {
    const float pmf = lightChoicePmf(scene);
    float pdf = 0.0f;
    for (const Light* l : scene.infiniteLights()) pdf += pmf * l->pdfLi(vec3(0.0f), wi, nullptr);
    return pdf;
}

SampledSpectrum vertexLe(const Scene& scene, const BDPTVertex& v, const BDPTVertex& to, const SampledWavelengths& wl) {
    SampledSpectrum Le(wl.size());
    if (!v.isLight()) return Le;
    const vec3 d = to.p - v.p;
    if (!(glm::dot(d, d) > 0)) return Le;
    const vec3 w = glm::normalize(d);
    if (v.isInfiniteLight()) {
        forEachEmission(scene, nullptr, -w, wl, [&](const Light&, const SampledSpectrum& e) { Le += e; });
        return Le;
    }
    if (v.type != BDPTVertexType::Surface) return Le;
    return v.si.areaLight->Le(textureQueryAt(v.si), v.si.ng, w, wl);
}

}  // namespace iris
