#include "integrators/path.h"

#include "core/error.h"
#include "core/sampling.h"
#include "integrators/transport_steps.h"
#include "materials/material.h"

namespace iris {

PathIntegrator::PathIntegrator(std::string type, const PathParams& params, int maxDepth, int rrDepth)
    : Integrator(std::move(type), params.maxDepth), params_(params),
      maxDepth_(maxDepth < 0 ? std::numeric_limits<int>::max() : maxDepth), rrDepth_(rrDepth),
      hideEmitters_(params.hideEmitters) {}

SampledSpectrum PathIntegrator::Li(const Scene& scene, const Ray& cameraRay, SampledWavelengths& wl, Sampler& sampler, Arena& arena,
                                   PathStats& stats) const {
    const int n = wl.size();
    SampledSpectrum L(n, 0.0f), beta(n, 1.0f);
    Ray ray = cameraRay;
    bool specularBounce = false;
    float bsdfPdf = 0.0f;       // solid-angle pdf of the previous BSDF sample (for MIS)
    vec3 prevP(0.0f);
    float etaScale = 1.0f;
    const bool haveLights = !scene.lights().empty();
    ++stats.paths;

    // depth = number of path segments so far (the camera ray is segment 1).
    for (int depth = 1;; ++depth) {
        ++stats.rays;
        const std::optional<SurfaceInteraction> hit = scene.intersect(ray);
        // Emission the path reached: full weight after the camera or a delta lobe, else MIS with
        // next-event estimation from the previous vertex.
        if (!(hideEmitters_ && depth == 1))
            forEachEmission(scene, hit ? &*hit : nullptr, ray.d, wl, [&](const Light& light, const SampledSpectrum& Le) {
                if (Le.isBlack()) return;
                if (depth == 1 || specularBounce) {
                    L += beta * Le;
                } else {
                    const float lightPdf = lightSamplingPdf(scene, light, prevP, ray.d, hit ? &*hit : nullptr);
                    L += beta * Le * powerHeuristic(bsdfPdf, lightPdf);
                }
            });
        if (!hit) break;
        const SurfaceInteraction& si = *hit;
        if (depth >= maxDepth_) break;

        const ShadingPoint sp = shadingPointAt(si);
        const Frame& frame = sp.shading;
        const BSDF* bsdf = si.material->getBSDF(sp, wl, arena);
        if (!bsdf) {  // pure boundary: continue straight through
            ray = si.spawnRay(ray.d);
            --depth;
            continue;
        }
        const vec3 wo = frame.toLocal(si.wo);

        // Next-event estimation (a path of depth+1 segments). Its 2D sample (the light and the point
        // on it) is drawn whether or not the BSDF can use it, so that the sample stream stays aligned.
        if (haveLights) {
            const vec2 uL = sampler.get2D();
            if (bsdf->hasNonSpecular()) L += directLight(scene, si, frame, *bsdf, wo, uL, wl, beta, stats);
        }

        // Sample the BSDF to continue the path.
        const float uc = sampler.get1D();
        const vec2 u = sampler.get2D();
        const auto bs = bsdf->sample(wo, uc, u, TransportMode::Radiance);
        if (!bs || bs->pdf <= 0 || bs->f.isBlack()) break;
        // A pass-through (null lobe, Mitsuba 3 src/bsdfs/mask.cpp, null.cpp) continues the ray
        // unchanged: it counts as a path segment (Mitsuba 3 path.cpp increments depth at every
        // valid intersection) and, being a delta lobe, the emitter it reaches gets MIS weight 1.
        const bool passThrough = bs->isNull();
        const vec3 wiWorld = passThrough ? glm::normalize(ray.d) : glm::normalize(frame.toWorld(bs->wi));
        if (params_.strictNormals && !passThrough && !sidesAgree(wiWorld, si.ng, bs->wi.z)) break;
        beta *= bs->f * (std::abs(bs->wi.z) / bs->pdf);
        specularBounce = bs->isSpecular();
        bsdfPdf = bs->pdf;
        if (bs->isTransmission()) etaScale *= sqr(bs->eta);
        prevP = si.p;
        ray = si.spawnRay(wiWorld);
        if (beta.isBlack() || beta.hasNonFinite()) break;

        // Russian roulette, on throughput with radiance scaling undone.
        const float uRR = sampler.get1D();
        if (depth >= rrDepth_) {
            const float q = rouletteSurvival((beta * etaScale).maxValue(), uRR);
            if (q == 0.0f) break;
            beta /= q;
        }
        arena.reset();
    }
    return L;
}

SampledSpectrum PathIntegrator::directLight(const Scene& scene, const SurfaceInteraction& si, const Frame& frame, const BSDF& bsdf,
                                            const vec3& wo, const vec2& uL, const SampledWavelengths& wl,
                                            const SampledSpectrum& beta, PathStats& stats) const {
    // The radiance is looked up last, for an unoccluded sample the BSDF does not make black (the
    // same contributions as looking it up first: no sample is drawn in between).
    std::optional<VertexLightSample> s =
        sampleLightAtSurface(scene, si.p, si.ng, frame, bsdf, wo, uL, wl, params_.strictNormals, RadianceLookup::Deferred);
    if (!s) return SampledSpectrum(wl.size());
    ++stats.rays;
    const LightSample& ls = s->ls;
    if (!(ls.infinite ? scene.visibleInfinite(si, ls.wi) : scene.visible(si, ls.pLight, ls.nLight))) return SampledSpectrum(wl.size());
    if (!resolveRadiance(*s, wl)) return SampledSpectrum(wl.size());
    if (s->light->isDelta()) return beta * s->f * ls.L / s->lightPdf;
    return beta * s->f * ls.L * (powerHeuristic(s->lightPdf, s->scatterPdf) / s->lightPdf);
}

PathParams readPathParams(const Properties& p) {
    PathParams pp;
    pp.maxDepth = p.getInt("max_depth", -1);
    if (pp.maxDepth < -1) failAt(p.locationOf("max_depth"), "max_depth must be -1 (unlimited) or >= 0");
    pp.rrDepth = p.getInt("rr_depth", 5);
    if (pp.rrDepth < 1) failAt(p.locationOf("rr_depth"), "rr_depth must be >= 1");
    pp.hideEmitters = p.getBool("hide_emitters", false);
    // Mitsuba 0.6's strictNormals (default false; Mitsuba 3 has no such test): see sidesAgree.
    pp.strictNormals = p.getBool("strict_normals", false);
    if (!p.children().empty()) failAt(p.children()[0]->location(), "unexpected <", p.children()[0]->tag(), "> inside <integrator>");
    return pp;
}

namespace {

std::shared_ptr<Integrator> createPath(const Properties& p) {
    const PathParams pp = readPathParams(p);
    return std::make_shared<PathIntegrator>(p.type(), pp, pp.maxDepth, pp.rrDepth);
}

/// Direct illumination: paths of two segments and no Russian roulette, whatever max_depth and
/// rr_depth say (they are read and recorded).
std::shared_ptr<Integrator> createDirect(const Properties& p) {
    return std::make_shared<PathIntegrator>(p.type(), readPathParams(p), 2, std::numeric_limits<int>::max());
}

}  // namespace

IRIS_REGISTER(IntegratorRegistry, "path", createPath);
IRIS_REGISTER(IntegratorRegistry, "direct", createDirect);

}  // namespace iris
