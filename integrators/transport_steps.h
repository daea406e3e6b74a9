// The steps every path-space integrator takes, written once (pbrt-v4 §13.4: SampleLd, the emission
// MIS of PathIntegrator::Li, Russian roulette; Mitsuba 3 src/integrators/path.cpp and volpath.cpp):
//   - choosing the light for next-event estimation (uniformly, Mitsuba 3 Scene::sample_emitter,
//     with the sample reused for the point on the light, as both Mitsubas do),
//   - sampling it from a surface point with the BSDF evaluated towards it (its radiance, at the
//     caller's choice, looked up only once the sample is known to contribute),
//   - the light-sampling pdf of a direction that reached a light (for MIS at an emitter hit),
//   - the emission a ray finds (the area light it hit, or every infinite light when it escaped),
//   - the strict-normals rule and Russian roulette.
// Visibility and the MIS weights stay with each integrator: `path` tests occlusion and uses the
// power heuristic, the volumetric ones estimate transmittance and combine pdf ratios over lanes.
#pragma once

#include <optional>

#include "materials/bsdf.h"
#include "materials/material.h"
#include "media/phase/phase_function.h"
#include "render/lights/light.h"
#include "render/scene.h"

namespace iris {

/// The light next-event estimation uses, and the probability of having chosen it.
struct LightChoice {
    const Light* light = nullptr;
    float pmf = 0.0f;
    float uReused = 0.0f;  // u stretched back to [0, 1) within the chosen light's interval
};

/// One of the scene's lights, chosen uniformly with u ∈ [0, 1) (Mitsuba 3 Scene::sample_emitter);
/// light is nullptr when the scene has none. uReused = u·n − i for light i of n (Mitsuba 0.6
/// DiscreteDistribution::sampleReuse, Mitsuba 3 Scene::sample_emitter's reused sample): uniform
/// in [0, 1) and independent of the choice, with u·n's fraction bits (⌊log2 n⌋ fewer than u's).
LightChoice chooseLight(const Scene& scene, float u);

/// The probability with which chooseLight picks any one light: 1 / (number of lights), 0 without
/// lights (used by the densities of MIS: next-event estimation and BDPT's light vertices).
inline float lightChoicePmf(const Scene& scene) {
    return scene.lights().empty() ? 0.0f : 1.0f / float(scene.lights().size());
}

/// The solid-angle density with which next-event estimation from `from` produces direction `d`
/// towards `light`, the light's choice included; `hit` is where d reached it (area lights) or
/// nullptr (infinite lights).
float lightSamplingPdf(const Scene& scene, const Light& light, const vec3& from, const vec3& d, const SurfaceInteraction* hit);

/// Mitsuba 0.6's strictNormals: direction w (world) leaves the surface on the same side of the
/// geometric normal ng as of the shading normal (wLocalZ, the direction's z in the shading frame).
/// Off by default in both Mitsubas (Mitsuba 3 has no such test): then every sampled direction is
/// followed, and light may leak through shading normals as it does there.
inline bool sidesAgree(const vec3& w, const vec3& ng, float wLocalZ) { return glm::dot(w, ng) * wLocalZ > 0; }

/// A light sample as seen from a path vertex (a surface point or a point in a medium), before its
/// visibility is known.
struct VertexLightSample {
    const Light* light = nullptr;
    LightSample ls;         // direction, radiance, the light's own pdf, the shadow ray's target
    float lightPdf = 0;     // chooseLight's pmf × ls.pdf
    float scatterPdf = 0;   // the pdf BSDF or phase sampling would have had for the direction
    SampledSpectrum f;      // f(wo, wi) · |cos θi| at a surface, the phase function in a medium
};

/// When next-event estimation looks up the light's radiance: with the sample (a black radiance
/// then ends the estimate before anything else), or only once the caller knows the sample
/// contributes (Light::sampleLiDeferred: the environment map's spectral lookup is skipped where the
/// BSDF is black or the shadow ray occluded; resolveRadiance looks it up).
enum class RadianceLookup { AtSample, Deferred };

/// chooseLight and the chosen light's sample from point p, its scattering terms (f, scatterPdf) not
/// yet set; nullopt when there is nothing to light with. One 2D sample does both, as in both
/// Mitsubas (0.6 Scene::sampleEmitterDirect, 3 Scene::sample_emitter_direction): uL.x chooses the
/// light and, stretched back to [0, 1), is reused with uL.y for the point on it, so the points a
/// stratified or low-discrepancy 2D set gives one light are again stratified (a separate 1D choice
/// would hand each light a random subset of them).
std::optional<VertexLightSample> sampleChosenLight(const Scene& scene, const vec3& p, const vec2& uL, const SampledWavelengths& wl,
                                                   RadianceLookup lookup = RadianceLookup::AtSample);

/// The sample's radiance looked up if its light deferred it (RadianceLookup::Deferred); false
/// when it is black (the sample contributes nothing).
bool resolveRadiance(VertexLightSample& s, const SampledWavelengths& wl);

/// Next-event estimation's sample at surface point p (geometric normal ng) with shading frame
/// `frame`, BSDF `bsdf` and wo (local), drawing its light and its point with uL (sampleChosenLight):
/// nullopt when the light gives nothing there, the BSDF is black towards it, or (strictNormals)
/// wi leaves on the other side of the geometric surface than of the shading one.
std::optional<VertexLightSample> sampleLightAtSurface(const Scene& scene, const vec3& p, const vec3& ng, const Frame& frame,
                                                      const BSDF& bsdf, const vec3& wo, const vec2& uL,
                                                      const SampledWavelengths& wl, bool strictNormals,
                                                      RadianceLookup lookup = RadianceLookup::AtSample);

/// The same at point p in a medium with phase function `phase` and wo (world, towards the previous
/// vertex).
std::optional<VertexLightSample> sampleLightInMedium(const Scene& scene, const vec3& p, const PhaseFunction& phase, const vec3& wo,
                                                     const vec2& uL, const SampledWavelengths& wl);

/// Calls emitted(light, Le) for the emission a ray with direction `d` finds: the area light of its
/// hit, or every infinite light when it escaped (hit = nullptr).
template <typename F>
void forEachEmission(const Scene& scene, const SurfaceInteraction* hit, const vec3& d, const SampledWavelengths& wl, F&& emitted);

/// The weight a ray along `dir` keeps when it crosses surface si without scattering (Mitsuba 3
/// volpath.cpp sample_emitter: eval_null_transmission at the hit), or nullopt when the surface blocks
/// it (any surface without a pass-through lobe: Material::transmitsShadowRays).
std::optional<SampledSpectrum> crossingWeight(const SurfaceInteraction& si, const vec3& dir, const SampledWavelengths& wl,
                                              Arena& arena);

/// The first ray of a light path (light tracing, BDPT): the light, chosen as next-event estimation
/// chooses it, and its emission sample, with the throughput the path starts with,
/// β = Le |cos θ| / (pmf · pdfPos · pdfDir) (pbrt-v4 §13.x GenerateLightSubpath, Mitsuba 3
/// Scene::sample_emitter_ray).
struct LightPathStart {
    const Light* light = nullptr;
    float pmf = 0.0f;
    LightEmission emission;
    SampledSpectrum beta;
};
std::optional<LightPathStart> startLightPath(const Scene& scene, float uLight, const vec2& uPos, const vec2& uDir,
                                             const SampledWavelengths& wl);

/// The shading-normal correction of the adjoint BSDF (Veach 1997 eq. 5.19; Mitsuba 3 ptracer.cpp):
/// a light path that arrives at a surface from woWorld (towards the previous vertex, the light
/// side) and leaves towards wiWorld carries f*(wo, wi) |wi·ns| times
/// |wo·ns| |wi·ng| / (|wo·ng| |wi·ns|), so that it estimates the integral a camera path estimates
/// with the shading normal ns (and the geometric normal ng). 0 where wo grazes the geometric surface.
float adjointShadingCorrection(const vec3& woWorld, const vec3& wiWorld, const vec3& ng, const vec3& ns);

/// Russian roulette (pbrt-v4 §13.4.4, Mitsuba 3 path.cpp): the path survives with probability
/// q = min(0.95, m), m its largest throughput (radiance scaling by η² undone). Returns q when it
/// survives (divide the throughput by it), 0 when the path ends.
inline float rouletteSurvival(float m, float u) {
    const float q = std::min(0.95f, m);
    return u < q ? q : 0.0f;
}

template <typename F>
void forEachEmission(const Scene& scene, const SurfaceInteraction* hit, const vec3& d, const SampledWavelengths& wl, F&& emitted) {
    if (!hit) {
        for (const Light* light : scene.infiniteLights()) emitted(*light, light->Le(TextureQuery{}, vec3(0.0f), d, wl));
        return;
    }
    if (hit->areaLight) emitted(*hit->areaLight, hit->areaLight->Le(textureQueryAt(*hit), hit->ng, hit->wo, wl));
}

}  // namespace iris
