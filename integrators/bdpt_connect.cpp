#include "integrators/bdpt_connect.h"

#include "integrators/transport_steps.h"

namespace iris {

namespace {

/// Nothing between a and b (every surface blocks; both ends offset off their surfaces).
bool unoccluded(const Scene& scene, const BDPTVertex& a, const BDPTVertex& b, PathStats& stats) {
    ++stats.rays;
    const vec3 d = b.p - a.p;
    const vec3 o = a.onSurface() ? offsetRayOrigin(a.p, a.ng, d) : a.p;
    const vec3 e = b.onSurface() ? offsetRayOrigin(b.p, b.ng, -d) : b.p;
    return !scene.occluded(Ray(o, e - o, 1.0f - 1e-4f));
}

/// Veach's correction (eq. 5.19) of light-subpath surface vertex q connected towards `to`.
float lightVertexCorrection(const BDPTVertex& q, const vec3& to) {
    return q.type == BDPTVertexType::Surface ? adjointShadingCorrection(q.si.wo, to, q.si.ng, q.shading.n) : 1.0f;
}

/// Strict normals: the connection leaves surface vertex v on one side of both of its normals.
bool strictOk(const BDPTVertex& v, const vec3& w, bool strict) {
    return !strict || v.type != BDPTVertexType::Surface || sidesAgree(w, v.si.ng, glm::dot(v.shading.n, w));
}

std::optional<BDPTConnection> cameraHitsEmitter(const Scene& scene, const BDPTVertex* camera, int t, const SampledWavelengths& wl) {
    const BDPTVertex& pt = camera[t - 1];
    if (!pt.isLight()) return std::nullopt;
    BDPTConnection c;
    c.L = pt.beta * vertexLe(scene, pt, camera[t - 2], wl);
    return c;
}

std::optional<BDPTConnection> lightVertexToCamera(const Scene& scene, const BDPTVertex* light, int s, bool strict, PathStats& stats) {
    const BDPTVertex& qs = light[s - 1];
    if (!qs.connectible()) return std::nullopt;
    const std::optional<SensorSample> ss = scene.description().camera.sensor->sampleWi(qs.p);
    if (!ss || !strictOk(qs, ss->wi, strict)) return std::nullopt;
    BDPTConnection c;
    c.sampled.type = BDPTVertexType::Camera;
    c.sampled.p = ss->pSensor;
    c.sampled.beta = SampledSpectrum(qs.beta.size(), ss->weight);
    c.L = qs.beta * vertexF(qs, c.sampled, TransportMode::Importance) *
          (qs.absCosShading(ss->wi) * lightVertexCorrection(qs, ss->wi) * ss->weight);
    if (c.L.isBlack() || !unoccluded(scene, qs, c.sampled, stats)) return std::nullopt;
    c.filmPos = ss->filmPos;
    return c;
}

std::optional<BDPTConnection> cameraVertexToLightPoint(const Scene& scene, const BDPTVertex* camera, int t, const SampledWavelengths& wl,
                                                       Sampler& sampler, bool strict, PathStats& stats) {
    const BDPTVertex& pt = camera[t - 1];
    const vec2 uL = sampler.get2D();
    if (!pt.connectible() || pt.type != BDPTVertexType::Surface) return std::nullopt;
    const std::optional<VertexLightSample> s =
        sampleLightAtSurface(scene, pt.p, pt.ng, pt.shading, *pt.bsdf, pt.shading.toLocal(pt.si.wo), uL, wl, strict);
    if (!s) return std::nullopt;
    ++stats.rays;
    const LightSample& ls = s->ls;
    if (!(ls.infinite ? scene.visibleInfinite(pt.si, ls.wi) : scene.visible(pt.si, ls.pLight, ls.nLight))) return std::nullopt;
    BDPTConnection c;
    BDPTVertex& v = c.sampled;
    v.type = BDPTVertexType::Light;
    v.light = s->light;
    v.infinite = s->light->type() == Light::Type::Infinite || s->light->type() == Light::Type::DeltaDirection;
    const float far = glm::length(pt.p - scene.bounds().center) + 2.0f * scene.bounds().radius;
    v.p = ls.infinite ? pt.p + far * ls.wi : ls.pLight;
    v.ng = ls.infinite ? vec3(0.0f) : ls.nLight;
    v.beta = ls.L / s->lightPdf;
    v.pdfFwd = lightOriginPdf(scene, v, pt);
    c.L = pt.beta * s->f * v.beta;  // f includes |cos θ| at pt
    return c;
}

std::optional<BDPTConnection> joinVertices(const Scene& scene, const BDPTVertex* light, const BDPTVertex* camera, int s, int t,
                                           bool strict, PathStats& stats) {
    const BDPTVertex &qs = light[s - 1], &pt = camera[t - 1];
    if (!qs.connectible() || !pt.connectible()) return std::nullopt;
    const vec3 d = pt.p - qs.p;
    const float dist2 = glm::dot(d, d);
    if (!(dist2 > 0)) return std::nullopt;
    const vec3 w = d / std::sqrt(dist2);  // from qs to pt
    if (!strictOk(qs, w, strict) || !strictOk(pt, -w, strict)) return std::nullopt;
    const float G = qs.absCosShading(w) * pt.absCosShading(w) / dist2;
    BDPTConnection c;
    c.L = qs.beta * vertexF(qs, pt, TransportMode::Importance) * vertexF(pt, qs, TransportMode::Radiance) * pt.beta *
          (G * lightVertexCorrection(qs, w));
    if (c.L.isBlack() || !unoccluded(scene, qs, pt, stats)) return std::nullopt;
    return c;
}

}  // namespace

std::optional<BDPTConnection> connectStrategy(const Scene& scene, const BDPTVertex* light, const BDPTVertex* camera, int s, int t,
                                              const SampledWavelengths& wl, Sampler& sampler, bool strictNormals, PathStats& stats) {
    // A camera subpath that escaped to infinity is only ever an emitter (pbrt-v4 ConnectBDPT).
    if (t > 1 && s != 0 && camera[t - 1].type == BDPTVertexType::Light) return std::nullopt;
    if (s == 0) return cameraHitsEmitter(scene, camera, t, wl);
    if (t == 1) return lightVertexToCamera(scene, light, s, strictNormals, stats);
    if (s == 1) return cameraVertexToLightPoint(scene, camera, t, wl, sampler, strictNormals, stats);
    return joinVertices(scene, light, camera, s, t, strictNormals, stats);
}

}  // namespace iris
