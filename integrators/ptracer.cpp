#include "integrators/ptracer.h"

#include "core/error.h"
#include "integrators/segment_transmittance.h"
#include "integrators/transport_steps.h"
#include "materials/material.h"
#include "render/splat_film.h"

namespace iris {

namespace {

/// Room for `crossings` more segments after a path of `segments` segments under max_depth.
bool fits(int segments, int crossings, int maxDepth) { return crossings <= maxDepth - segments; }

/// Where the sensor cannot see, or a segment is blocked, nothing is splatted.
void splatIfVisible(const Scene& scene, const vec3& p, const vec3& ng, const SensorSample& s, const SampledSpectrum& L,
                    int segments, int maxDepth, SampledWavelengths& wl, Arena& arena, PathStats& stats, SplatFilm& splats) {
    if (L.isBlack()) return;
    const auto t = segmentTransmittance(scene, p, ng, s.pSensor, wl, true, arena, stats);
    if (!t || !fits(segments, t->second, maxDepth)) return;
    splats.splat(s.filmPos, L * t->first, wl);
}

}  // namespace

PTracerIntegrator::PTracerIntegrator(const PathParams& params, int samplesPerPass)
    : Integrator("ptracer", params.maxDepth), params_(params),
      maxDepth_(params.maxDepth < 0 ? std::numeric_limits<int>::max() : params.maxDepth), samplesPerPass_(samplesPerPass) {}

SampledSpectrum PTracerIntegrator::Li(const Scene&, const Ray&, SampledWavelengths&, Sampler&, Arena&, PathStats&) const {
    fail("the ptracer integrator splats its paths on the film: it renders through the renderer, not per camera ray");
}

SampledSpectrum PTracerIntegrator::sample(const Scene& scene, const Ray&, SampledWavelengths& wl, Sampler& sampler, Arena& arena,
                                          PathStats& stats, SplatFilm& splats) const {
    ++stats.paths;
    // Mitsuba 3 ptracer.cpp sample(): emitters seen directly (paths of one segment), then the light path.
    if (maxDepth_ >= 1 && !params_.hideEmitters) splatVisibleEmitter(scene, wl, sampler, arena, stats, splats);
    traceLightPath(scene, wl, sampler, arena, stats, splats);
    return SampledSpectrum(wl.size());
}

// A point on an area emitter connected to the sensor, Le |cos θ_light| W / (pmf · pdfPos) (Mitsuba 3
// ptracer.cpp sample_visible_emitters). Delta lights cannot be seen.
void PTracerIntegrator::splatVisibleEmitter(const Scene& scene, SampledWavelengths& wl, Sampler& sampler, Arena& arena,
                                            PathStats& stats, SplatFilm& splats) const {
    const float uLight = sampler.get1D();
    const vec2 uPos = sampler.get2D(), uDir = sampler.get2D();
    const LightChoice choice = chooseLight(scene, uLight);
    if (!choice.light || choice.light->isDelta()) return;
    if (choice.light->type() == Light::Type::Infinite) return splatVisibleInfinite(scene, *choice.light, choice.pmf, uPos, wl, arena, stats, splats);
    const Sensor& sensor = *scene.description().camera.sensor;
    const std::optional<LightEmission> e = choice.light->sampleLe(uPos, uDir, wl, scene.bounds());
    if (!e) return;
    const std::optional<SensorSample> s = sensor.sampleWi(e->at.p);
    if (!s) return;
    const SampledSpectrum Le = choice.light->Le(e->at, e->n, s->wi, wl);
    const float cosLight = std::abs(glm::dot(e->n, s->wi));
    splatIfVisible(scene, e->at.p, e->n, *s, Le * (cosLight * s->weight / (choice.pmf * e->pdfPos)), 1, maxDepth_, wl, arena, stats,
                   splats);
}

// An infinite light seen directly: a direction drawn from the sensor (a film position uniform over
// the image and the filter's margin around it), not from the light as Mitsuba 3 does — its
// directions fall in the view with the view's share of the sphere only, which leaves each pixel a
// handful of hits in hundreds of passes. Le W / (pmf · pdf), pdf = the pinhole's density of that
// direction over the enlarged film (render/sensors/perspective.cpp). Sensors without a pinhole see
// one direction: no density can reach it, and nothing is splatted.
void PTracerIntegrator::splatVisibleInfinite(const Scene& scene, const Light& light, float pmf, const vec2& u, SampledWavelengths& wl,
                                             Arena& arena, PathStats& stats, SplatFilm& splats) const {
    const Sensor& sensor = *scene.description().camera.sensor;
    const std::optional<vec3> pin = sensor.pinhole();
    if (!pin) return;
    const float m = splats.margin(), w = float(splats.width()), h = float(splats.height());
    const vec2 filmPos(-m + u.x * (w + 2 * m), -m + u.y * (h + 2 * m));
    const vec3 d = glm::normalize(sensor.generateRay(filmPos).d);
    const std::optional<SensorSample> s = sensor.sampleWi(*pin + d);
    if (!s) return;
    const float pdf = sensor.pdfDirection(d) * (w * h) / ((w + 2 * m) * (h + 2 * m));
    const SampledSpectrum Le = light.Le(TextureQuery{}, vec3(0.0f), d, wl);
    const float far = glm::length(*pin - scene.bounds().center) + 2.0f * scene.bounds().radius;
    const SensorSample toFar{*pin, s->wi, far, s->filmPos, s->weight};
    splatIfVisible(scene, *pin + far * d, vec3(0.0f), toFar, Le * (s->weight / (pmf * pdf)), 1, maxDepth_, wl, arena, stats, splats);
}

// The light path (Mitsuba 3 ptracer.cpp trace_light_ray; Veach 1997 §10.2): at every vertex with a
// non-delta lobe, the connection to the sensor β f*(wo, wi) |cos θ_i| C W, with the adjoint BSDF
// (TransportMode::Importance) and Veach's shading-normal correction C (eq. 5.19); then the path
// continues by sampling the adjoint BSDF, its throughput × f* |cos θ| / pdf × C.
void PTracerIntegrator::traceLightPath(const Scene& scene, SampledWavelengths& wl, Sampler& sampler, Arena& arena,
                                       PathStats& stats, SplatFilm& splats) const {
    const float uLight = sampler.get1D();
    const vec2 uPos = sampler.get2D(), uDir = sampler.get2D();
    const std::optional<LightPathStart> start = startLightPath(scene, uLight, uPos, uDir, wl);
    if (!start) return;
    const Sensor& sensor = *scene.description().camera.sensor;
    SampledSpectrum beta = start->beta;
    const float beta0 = beta.maxValue();
    Ray ray = start->emission.ray;
    // depth = segments so far (the ray from the light is segment 1); a connection adds one.
    for (int depth = 1; depth < maxDepth_; ++depth) {
        ++stats.rays;
        const std::optional<SurfaceInteraction> hit = scene.intersect(ray);
        if (!hit) return;
        const SurfaceInteraction& si = *hit;
        const ShadingPoint sp = shadingPointAt(si);
        const Frame& frame = sp.shading;
        const BSDF* bsdf = si.material->getBSDF(sp, wl, arena);
        if (!bsdf) {  // pure boundary: continue straight through
            ray = si.spawnRay(ray.d);
            --depth;
            continue;
        }
        const vec3 wo = frame.toLocal(si.wo);
        const std::optional<SensorSample> s = bsdf->hasNonSpecular() ? sensor.sampleWi(si.p) : std::nullopt;
        if (s) {
            const vec3 wi = frame.toLocal(s->wi);
            if (!params_.strictNormals || sidesAgree(s->wi, si.ng, wi.z)) {
                const float c = shadingCorrection_ ? adjointShadingCorrection(si.wo, s->wi, si.ng, frame.n) : 1.0f;
                const SampledSpectrum f = bsdf->eval(wo, wi, TransportMode::Importance);
                splatIfVisible(scene, si.p, si.ng, *s, beta * f * (std::abs(wi.z) * c * s->weight), depth + 1, maxDepth_, wl,
                               arena, stats, splats);
            }
        }
        const float uc = sampler.get1D();
        const vec2 u = sampler.get2D();
        const auto bs = bsdf->sample(wo, uc, u, TransportMode::Importance);
        if (!bs || bs->pdf <= 0 || bs->f.isBlack()) return;
        const vec3 wiWorld = bs->isNull() ? glm::normalize(ray.d) : glm::normalize(frame.toWorld(bs->wi));
        if (params_.strictNormals && !bs->isNull() && !sidesAgree(wiWorld, si.ng, bs->wi.z)) return;
        const float c = shadingCorrection_ ? adjointShadingCorrection(si.wo, wiWorld, si.ng, frame.n) : 1.0f;
        beta *= bs->f * (std::abs(bs->wi.z) * c / bs->pdf);
        ray = si.spawnRay(wiWorld);
        if (beta.isBlack() || beta.hasNonFinite()) return;
        // Russian roulette on the throughput relative to the start (importance is not scaled by
        // refraction, so there is no η² to undo).
        const float uRR = sampler.get1D();
        if (depth >= params_.rrDepth) {
            const float q = rouletteSurvival(beta.maxValue() / beta0, uRR);
            if (q == 0.0f) return;
            beta /= q;
        }
        arena.reset();
    }
}

namespace {

std::shared_ptr<Integrator> createPTracer(const Properties& p) {
    const int samplesPerPass = p.getInt("samples_per_pass", -1);
    if (samplesPerPass == 0 || samplesPerPass < -1) failAt(p.locationOf("samples_per_pass"), "samples_per_pass must be >= 1");
    return std::make_shared<PTracerIntegrator>(readPathParams(p), samplesPerPass);
}

}  // namespace

IRIS_REGISTER(IntegratorRegistry, "ptracer", createPTracer);

}  // namespace iris
