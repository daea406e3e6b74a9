#include "integrators/path.h"

#include "core/error.h"
#include "core/sampling.h"
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
    const auto& lights = scene.lights();
    const float lightSelectPdf = lights.empty() ? 0.0f : 1.0f / float(lights.size());
    ++stats.paths;

    // depth = number of path segments so far (the camera ray is segment 1).
    for (int depth = 1;; ++depth) {
        ++stats.rays;
        const std::optional<SurfaceInteraction> hit = scene.intersect(ray);
        const bool countEmission = !(hideEmitters_ && depth == 1);

        if (!hit) {
            if (countEmission)
                for (const Light* light : scene.infiniteLights()) {
                    const SampledSpectrum Le = light->Le(TextureQuery{}, vec3(0.0f), ray.d, wl);
                    if (depth == 1 || specularBounce) {
                        L += beta * Le;
                    } else {
                        const float lightPdf = lightSelectPdf * light->pdfLi(prevP, ray.d, nullptr);
                        L += beta * Le * powerHeuristic(bsdfPdf, lightPdf);
                    }
                }
            break;
        }
        const SurfaceInteraction& si = *hit;

        // Emission from an area light that the path hit.
        if (si.areaLight && countEmission) {
            const SampledSpectrum Le = si.areaLight->Le(textureQueryAt(si), si.ng, si.wo, wl);
            if (!Le.isBlack()) {
                if (depth == 1 || specularBounce) {
                    L += beta * Le;
                } else {
                    const float lightPdf = lightSelectPdf * si.areaLight->pdfLi(prevP, ray.d, &si);
                    L += beta * Le * powerHeuristic(bsdfPdf, lightPdf);
                }
            }
        }
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

        // Next-event estimation (a path of depth+1 segments).
        if (!lights.empty() && bsdf->hasNonSpecular()) {
            const float uLight = sampler.get1D();
            const vec2 uL = sampler.get2D();
            const int li = std::min(int(uLight * lights.size()), int(lights.size()) - 1);
            const Light& light = *lights[li];
            if (const auto ls = light.sampleLi(si.p, uL, wl); ls && ls->pdf > 0 && !ls->L.isBlack()) {
                const vec3 wi = frame.toLocal(ls->wi);
                SampledSpectrum f = bsdf->eval(wo, wi, TransportMode::Radiance);
                // Light leaks through shading normals: require the geometric sides to agree.
                const bool sideOk = glm::dot(ls->wi, si.ng) * wi.z > 0;
                if (sideOk && !f.isBlack()) {
                    ++stats.rays;
                    const bool vis = ls->infinite ? scene.visibleInfinite(si, ls->wi) : scene.visible(si, ls->pLight, ls->nLight);
                    if (vis) {
                        f *= std::abs(wi.z);
                        if (light.isDelta()) {
                            L += beta * f * ls->L / (lightSelectPdf * ls->pdf);
                        } else {
                            const float lightPdf = lightSelectPdf * ls->pdf;
                            const float scatterPdf = bsdf->pdf(wo, wi, TransportMode::Radiance);
                            L += beta * f * ls->L * (powerHeuristic(lightPdf, scatterPdf) / lightPdf);
                        }
                    }
                }
            }
        } else if (!lights.empty()) {
            // Keep the sample stream aligned regardless of the branch taken.
            sampler.get1D();
            sampler.get2D();
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
        if (!passThrough && glm::dot(wiWorld, si.ng) * bs->wi.z <= 0) break;  // sampled across the geometric surface
        beta *= bs->f * (std::abs(bs->wi.z) / bs->pdf);
        specularBounce = bs->isSpecular();
        bsdfPdf = bs->pdf;
        if (bs->isTransmission()) etaScale *= sqr(bs->eta);
        prevP = si.p;
        ray = si.spawnRay(wiWorld);
        if (beta.isBlack() || beta.hasNonFinite()) break;

        // Russian roulette (pbrt-v4 §13.4.4), on throughput with radiance scaling undone.
        const float uRR = sampler.get1D();
        if (depth >= rrDepth_) {
            const float q = std::min(0.95f, (beta * etaScale).maxValue());
            if (uRR >= q) break;
            beta /= q;
        }
        arena.reset();
    }
    return L;
}

PathParams readPathParams(const Properties& p) {
    PathParams pp;
    pp.maxDepth = p.getInt("max_depth", -1);
    if (pp.maxDepth < -1) failAt(p.locationOf("max_depth"), "max_depth must be -1 (unlimited) or >= 0");
    pp.rrDepth = p.getInt("rr_depth", 5);
    if (pp.rrDepth < 1) failAt(p.locationOf("rr_depth"), "rr_depth must be >= 1");
    pp.hideEmitters = p.getBool("hide_emitters", false);
    // Mitsuba 0.6's strictNormals (default false) is accepted and has no effect: iris always
    // discards a sampled direction whose geometric and shading sides disagree (strict for wi).
    p.getBool("strict_normals", false);
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
