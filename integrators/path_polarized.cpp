// The polarized form of `path` and `direct` (docs/polarization.md): PathIntegrator::Li's loop with
// the throughput as Stokes rows (integrators/stokes_throughput.h) and every BSDF as its Mueller
// matrix (BSDF::evalMueller, sampleMueller), as Mitsuba 3's polarized variants run
// src/integrators/path.cpp: the BSDF's local-frame matrix goes to world space by rotating its
// bases (SurfaceInteraction::to_world_mueller), emitters are unpolarized. The sample stream, the
// MIS weights and Russian roulette (on the unpolarized weight, row 0's first entry) are Li's, so
// a scene of depolarizing BSDFs renders the spectral image's S0.
#include "core/sampling.h"
#include "integrators/path.h"
#include "integrators/stokes_throughput.h"
#include "integrators/transport_steps.h"
#include "materials/material.h"
#include "spectral/stokes_basis.h"

namespace iris {

namespace {

/// Next-event estimation at si as in PathIntegrator::directLight, with the BSDF's Mueller matrix.
void directLightStokes(const Scene& scene, const SurfaceInteraction& si, const Frame& frame, const BSDF& bsdf, const vec3& wo,
                       const vec2& uL, const SampledWavelengths& wl, const StokesThroughput& T,
                       bool strictNormals, PathStats& stats, StokesVector& est) {
    std::optional<VertexLightSample> s = sampleChosenLight(scene, si.p, uL, wl, RadianceLookup::Deferred);
    if (!s) return;
    const vec3 wi = frame.toLocal(s->ls.wi);
    if (strictNormals && !sidesAgree(s->ls.wi, si.ng, wi.z)) return;
    // The shadow ray before the matrix (a Mueller matrix costs several times the spectral f, and an
    // occluded light needs none); a BSDF without transmission is black on the other side, so no
    // ray is traced there. Contributions are the same as matrix-first.
    if (!(bsdf.flags() & kBSDFTransmission) && !(wi.z * wo.z > 0)) return;
    ++stats.rays;
    const LightSample& ls = s->ls;
    if (!(ls.infinite ? scene.visibleInfinite(si, ls.wi) : scene.visible(si, ls.pLight, ls.nLight))) return;
    MuellerSpectrum M = bsdf.evalMueller(wo, wi, TransportMode::Radiance);
    M *= std::abs(wi.z);  // in place: no copy of the matrix
    if (M(0, 0).isBlack()) return;
    if (!resolveRadiance(*s, wl)) return;  // looked up last, as in PathIntegrator::directLight
    if (s->light->isDelta()) return T.addThrough(M, ls.L, 1.0f / s->lightPdf, est);
    const float scatterPdf = bsdf.pdf(wo, wi, TransportMode::Radiance);
    T.addThrough(M, ls.L, powerHeuristic(s->lightPdf, scatterPdf) / s->lightPdf, est);
}

}  // namespace

void PathIntegrator::LiStokes(const Scene& scene, const Ray& cameraRay, SampledWavelengths& wl, Sampler& sampler, Arena& arena,
                              PathStats& stats, StokesEstimate& est) const {
    const int n = wl.size();
    StokesThroughput T(est.rows, n, est.rows > 1 ? est.basis : stokesBasis(-glm::normalize(cameraRay.d)));
    Ray ray = cameraRay;
    bool specularBounce = false;
    float bsdfPdf = 0.0f;
    vec3 prevP(0.0f);
    float etaScale = 1.0f;
    const bool haveLights = !scene.lights().empty();
    ++stats.paths;

    for (int depth = 1;; ++depth) {
        ++stats.rays;
        const std::optional<SurfaceInteraction> hit = scene.intersect(ray);
        if (!(hideEmitters_ && depth == 1))
            forEachEmission(scene, hit ? &*hit : nullptr, ray.d, wl, [&](const Light& light, const SampledSpectrum& Le) {
                if (Le.isBlack()) return;
                if (depth == 1 || specularBounce) return T.addUnpolarized(Le, 1.0f, est.S);
                const float lightPdf = lightSamplingPdf(scene, light, prevP, ray.d, hit ? &*hit : nullptr);
                T.addUnpolarized(Le, powerHeuristic(bsdfPdf, lightPdf), est.S);
            });
        if (!hit) break;
        const SurfaceInteraction& si = *hit;
        if (depth >= maxDepth_) break;

        const ShadingPoint sp = shadingPointAt(si);
        const Frame& frame = sp.shading;
        const BSDF* bsdf = si.material->getBSDF(sp, wl, arena);
        if (!bsdf) {
            ray = si.spawnRay(ray.d);
            --depth;
            continue;
        }
        const vec3 wo = frame.toLocal(si.wo);
        // The rows now act on the basis the BSDF's matrices leave in (Mitsuba 3 to_world_mueller).
        T.changeBasis(frame.toWorld(wo), frame.toWorld(stokesBasis(wo)));

        if (haveLights) {
            const vec2 uL = sampler.get2D();
            if (bsdf->hasNonSpecular())
                directLightStokes(scene, si, frame, *bsdf, wo, uL, wl, T, params_.strictNormals, stats, est.S);
        }

        const float uc = sampler.get1D();
        const vec2 u = sampler.get2D();
        auto ps = bsdf->sampleMueller(wo, uc, u, TransportMode::Radiance);
        if (!ps || ps->s.pdf <= 0 || ps->s.f.isBlack()) break;
        const BSDFSample& bs = ps->s;
        const bool passThrough = bs.isNull();
        const vec3 wiWorld = passThrough ? glm::normalize(ray.d) : glm::normalize(frame.toWorld(bs.wi));
        if (params_.strictNormals && !passThrough && !sidesAgree(wiWorld, si.ng, bs.wi.z)) break;
        ps->M *= std::abs(bs.wi.z) / bs.pdf;  // in place: no copy of the matrix
        T.apply(ps->M, frame.toWorld(stokesBasis(-bs.wi)));
        specularBounce = bs.isSpecular();
        bsdfPdf = bs.pdf;
        if (bs.isTransmission()) etaScale *= sqr(bs.eta);
        prevP = si.p;
        ray = si.spawnRay(wiWorld);
        if (T.isBlack() || T.hasNonFinite()) break;

        const float uRR = sampler.get1D();
        if (depth >= rrDepth_) {
            const float q = rouletteSurvival((T.intensity() * etaScale).maxValue(), uRR);
            if (q == 0.0f) break;
            T *= 1.0f / q;  // (the spectral loop divides: the two differ by rounding only)
        }
        arena.reset();
    }
}

}  // namespace iris
