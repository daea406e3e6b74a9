#include "integrators/bdpt_walk.h"

#include "integrators/transport_steps.h"

namespace iris {

namespace {

/// Continues the subpath path[0..n) along `ray` with throughput β, the direction drawn with
/// solid-angle density pdfFwd (pbrt-v4 RandomWalk). Returns the vertex count.
int randomWalk(const Scene& scene, Ray ray, SampledWavelengths& wl, Sampler& sampler, Arena& arena, PathStats& stats,
               SampledSpectrum beta, float pdfFwd, TransportMode mode, const WalkParams& params, BDPTVertex* path, int n,
               int maxVertices) {
    const float beta0 = beta.maxValue();  // Russian roulette acts on the throughput relative to the start
    float etaScale = 1.0f;                 // radiance scaling by η², undone for the roulette (as `path`)
    while (n < maxVertices) {
        ++stats.rays;
        const std::optional<SurfaceInteraction> hit = scene.intersect(ray);
        if (!hit) {
            if (mode == TransportMode::Radiance) path[n++] = escapedVertex(ray, beta, pdfFwd);
            break;
        }
        const SurfaceInteraction& si = *hit;
        const ShadingPoint sp = shadingPointAt(si);
        const BSDF* bsdf = si.material->getBSDF(sp, wl, arena);
        if (!bsdf) {  // a boundary only: no vertex (pbrt-v4 SkipIntersection)
            ray = si.spawnRay(ray.d);
            continue;
        }
        BDPTVertex& v = path[n] = surfaceVertex(si, sp.shading, bsdf, beta, pdfFwd, path[n - 1]);
        if (++n >= maxVertices) break;
        const vec3 wo = sp.shading.toLocal(si.wo);
        const float uc = sampler.get1D();
        const vec2 u = sampler.get2D();
        const auto bs = bsdf->sample(wo, uc, u, mode);
        if (!bs || !(bs->pdf > 0) || bs->f.isBlack()) break;
        const vec3 wi = bs->isNull() ? glm::normalize(ray.d) : glm::normalize(sp.shading.toWorld(bs->wi));
        if (params.strictNormals && !bs->isNull() && !sidesAgree(wi, si.ng, bs->wi.z)) break;
        const float c = mode == TransportMode::Importance ? adjointShadingCorrection(si.wo, wi, si.ng, sp.shading.n) : 1.0f;
        beta *= bs->f * (std::abs(bs->wi.z) * c / bs->pdf);
        if (mode == TransportMode::Radiance && bs->isTransmission()) etaScale *= sqr(bs->eta);
        pdfFwd = bs->pdf;
        // The reverse density: of sampling wo from wi in the other transport mode (pbrt-v4).
        const TransportMode other = mode == TransportMode::Radiance ? TransportMode::Importance : TransportMode::Radiance;
        float pdfRev = bsdf->pdf(bs->wi, wo, other);
        if (bs->isSpecular()) {
            v.delta = true;
            pdfFwd = pdfRev = 0.0f;
        }
        path[n - 2].pdfRev = convertDensity(v, pdfRev, path[n - 2]);
        ray = si.spawnRay(wi);
        if (beta.isBlack() || beta.hasNonFinite()) break;
        const float uRR = sampler.get1D();
        if (n - 1 >= params.rrDepth) {  // n − 1 segments so far
            const float q = rouletteSurvival((beta * etaScale).maxValue() / beta0, uRR);
            if (q == 0.0f) break;
            beta /= q;
        }
    }
    return n;
}

}  // namespace

int cameraSubpath(const Scene& scene, const Ray& ray, SampledWavelengths& wl, Sampler& sampler, Arena& arena, PathStats& stats,
                  const WalkParams& params, BDPTVertex* path, int maxVertices) {
    if (maxVertices == 0) return 0;
    BDPTVertex& camera = path[0] = BDPTVertex{};
    camera.type = BDPTVertexType::Camera;
    camera.beta = SampledSpectrum(wl.size(), 1.0f);
    camera.p = ray.o;
    const float pdfDir = scene.description().camera.sensor->pdfDirection(glm::normalize(ray.d));
    return randomWalk(scene, ray, wl, sampler, arena, stats, camera.beta, pdfDir, TransportMode::Radiance, params, path, 1,
                      maxVertices);
}

int lightSubpath(const Scene& scene, SampledWavelengths& wl, Sampler& sampler, Arena& arena, PathStats& stats,
                 const WalkParams& params, BDPTVertex* path, int maxVertices) {
    const float uLight = sampler.get1D();
    const vec2 uPos = sampler.get2D(), uDir = sampler.get2D();
    if (maxVertices == 0) return 0;
    const std::optional<LightPathStart> start = startLightPath(scene, uLight, uPos, uDir, wl);
    if (!start) return 0;
    const LightEmission& e = start->emission;
    BDPTVertex& light = path[0] = BDPTVertex{};
    light.type = BDPTVertexType::Light;
    light.light = start->light;
    light.beta = e.L;
    light.p = glm::dot(e.n, e.n) > 0 ? e.at.p : e.ray.o;
    light.ng = e.n;
    light.infinite = start->light->type() == Light::Type::Infinite || start->light->type() == Light::Type::DeltaDirection;
    light.pdfFwd = start->pmf * e.pdfPos;
    const int n = randomWalk(scene, e.ray, wl, sampler, arena, stats, start->beta, e.pdfDir, TransportMode::Importance, params, path, 1,
                             maxVertices);
    if (light.infinite) {
        // Lights at infinity (pbrt-v4 GenerateLightSubpath): the second vertex's density is the
        // disk's, projected; the first's the directional density of every infinite light.
        if (n > 1) {
            path[1].pdfFwd = e.pdfPos;
            if (path[1].onSurface()) path[1].pdfFwd *= std::abs(glm::dot(e.ray.d, path[1].ng));
        }
        light.pdfFwd = infiniteLightDensity(scene, -e.ray.d);
    }
    return n;
}

}  // namespace iris
