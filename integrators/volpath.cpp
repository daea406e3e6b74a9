// Volumetric path tracing with spectral transport: Mitsuba 3's `volpath` and `volpathmis`
// (parameters max_depth, rr_depth, hide_emitters as for `path`).
//
// Both follow the null-scattering path integral (Miller, Georgiev & Jarosz 2019, "A
// Null-Scattering Path Integral Formulation of Light Transport", SIGGRAPH; the estimator layout of
// pbrt-v4 §14.2, VolPathIntegrator): free-flight distances are sampled against each medium's
// majorant σ_maj for one *sampling lane* h of the path's wavelengths (delta tracking: a real or a
// null collision chosen by σ_t and σ_n over σ_maj in lane h; at a real collision the path always
// scatters, weighted per lane by σ_s/σ_t — absorption is a weight, not an event, as in Mitsuba 3's
// volpath, so that a lane whose albedo is 0 where another's is not never ends the other lanes);
// shadow rays estimate transmittance by ratio tracking. Every lane k carries, besides the
// throughput β = f/p_h, the ratio r_u[k] = p_k/p_h of the pdf the path would have had if lane k
// had been sampled (and r_l[k] for the light-sampling strategy of the last vertex). A contribution
// f·Le is divided by
//   volpath:    p_h alone            — β·Le/r_u[h] (r_u[h] = 1): Mitsuba 3's volpath, unbiased
//               but noisy in media whose σ_t varies with wavelength;
//   volpathmis: the mean over lanes  — β·Le/mean_k r_u[k]: one-sample MIS over the lanes with the
//               balance heuristic (hero wavelength spectral MIS, Wilkie et al. 2014 §4; pbrt-v4
//               eq. 14.19), as Mitsuba 3's volpathmis does;
// and by the sum of both strategies' ratios where next-event estimation and BSDF/phase sampling
// could both have produced the last segment (balance heuristic, Veach 1997 §9.2).
// The sampling lane: spectral mode lane 0 (the lanes are exchangeable, spectral/wavelengths.h, so
// lane 0 is a uniform choice among them); RGB mode a uniformly chosen channel (as Mitsuba 3's
// volpath does). After a dispersive refraction leaves only the hero wavelength, both use lane 0
// alone (the other lanes no longer carry a sample).
//
// Mitsuba 3's conventions (src/integrators/volpath.cpp): depth counts real scattering events on
// surfaces and in media, not null-BSDF boundary crossings; a path stops when depth reaches
// max_depth; emitter sampling at a surface needs depth + 1 < max_depth (depth before this
// bounce), in a medium depth < max_depth (depth after this scattering event), so that both allow
// max_depth − 1 scattering vertices with next-event estimation; a shape with an interior or exterior
// medium is a medium transition: the ray's medium becomes the exterior one when it leaves along
// the geometric normal, the interior one otherwise. A sampled pass-through lobe (kBSDFNull: `null`,
// the transparent part of `mask`, the transmission of `thindielectric`) is no bounce either: depth,
// the last scattering vertex and its pdf stay as they were (volpath.cpp: non_null_bsdf). Shadow rays
// cross surfaces whose BSDF has a pass-through lobe with its weight (BSDF::nullTransmission, Mitsuba
// 3's eval_null_transmission in sample_emitter); any other surface blocks them. Mitsuba 0.6 differs:
// its volpath counts a null crossing as an interaction on the path and on shadow rays
// (docs/media.md). A medium with a volumelight emits at every collision (addMediumEmission).
// Polarized mode (LiStokes, docs/polarization.md) runs the same walk with the throughput as Stokes
// rows (integrators/stokes_throughput.h), BSDFs and phase functions as Mueller matrices and shadow
// rays collecting the matrices of the pass-through surfaces they cross (integrators/
// volpath_stokes.h); the `Polarized = false` instantiation is the spectral walk, unchanged.
#include "core/error.h"
#include "core/sampling.h"
#include "integrators/path.h"
#include "integrators/transport_steps.h"
#include "integrators/volpath_stokes.h"
#include "materials/material.h"
#include "spectral/stokes_basis.h"

namespace iris {
namespace {

constexpr uint32_t kPassThroughLobe = kBSDFNull | kBSDFTransmission | kBSDFSpecular;

/// What a path carries besides its position (see the file comment): its radiance and throughput
/// as spectra, or in polarized mode as a Stokes estimate and Stokes rows.
template <bool Polarized>
struct PathState {
    std::conditional_t<Polarized, StokesVector, SampledSpectrum> L;
    std::conditional_t<Polarized, StokesThroughput, SampledSpectrum> beta;
    SampledSpectrum rU, rL;
    int depth = 0;
    bool specularBounce = false;
    float etaScale = 1.0f;
    vec3 prevP{0.0f};  // the last real scattering vertex (for light pdfs)
    const Medium* medium = nullptr;
    bool terminated = false;
};

/// The medium on the far side of surface `si` for a ray leaving it along d (Mitsuba 3
/// SurfaceInteraction::target_medium), or `current` when the shape is no medium transition.
const Medium* mediumAfter(const Scene& scene, const SurfaceInteraction& si, const vec3& d, const Medium* current) {
    const ShapeDescription& s = scene.shape(si.shapeIndex);
    if (!s.interior && !s.exterior) return current;
    return glm::dot(d, si.ng) > 0 ? s.exterior.get() : s.interior.get();
}

/// The weight a shadow ray along `dir` keeps when it crosses surface si (Mitsuba 3 volpath.cpp
/// sample_emitter: eval_null_transmission at the hit): applied to T; false when the surface blocks.
/// Polarized: T is a ShadowMueller and the weight the BSDF's nullTransmissionMueller.
template <typename Transmittance>
bool crossSurface(const SurfaceInteraction& si, const vec3& dir, const SampledWavelengths& wl, Arena& arena, Transmittance& T) {
    if constexpr (std::is_same_v<Transmittance, SampledSpectrum>) {
        const std::optional<SampledSpectrum> w = crossingWeight(si, dir, wl, arena);  // transport_steps.h
        if (!w || w->isBlack()) return false;
        T *= *w;
        return true;
    } else {
        if (!si.material->transmitsShadowRays()) return false;
        const ShadingPoint sp = shadingPointAt(si);
        SampledWavelengths own = wl;  // a nested dispersive BSDF may end lanes: of this query, not of the path
        const BSDF* bsdf = si.material->getBSDF(sp, own, arena);
        if (!bsdf) return true;  // a boundary only
        const std::optional<MuellerSpectrum> w = bsdf->nullTransmissionMueller(sp.shading.toLocal(-dir));
        if (!w) return false;
        T.cross(*w, sp.shading);
        return !T.isBlack();
    }
}

/// A surface that passes the ray on unchanged, which volpath treats as a boundary (no bounce, no
/// random numbers): no BSDF, or only a pass-through lobe of weight 1 (`null`; not a polarizing
/// filter, whose lobe is sampled like any other).
template <bool Polarized>
bool passesUnchanged(const BSDF* bsdf, const vec3& wo) {
    if (!bsdf) return true;
    if (bsdf->flags() != (kBSDFNull | kBSDFTransmission | kBSDFSpecular)) return false;
    if constexpr (Polarized) {
        const std::optional<MuellerSpectrum> m = bsdf->nullTransmissionMueller(wo);
        if (!m || m->depolarizing()) return false;
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j)
                for (int k = 0; k < m->size(); ++k)
                    if ((*m)(i, j)[k] != (i == j ? 1.0f : 0.0f)) return false;
        return true;
    } else {
        const std::optional<SampledSpectrum> t = bsdf->nullTransmission(wo);
        if (!t) return false;
        for (int k = 0; k < t->size(); ++k)
            if ((*t)[k] != 1.0f) return false;
        return true;
    }
}

/// Per-path random numbers for the variable number of tracking steps: a generator seeded from two
/// sampler values, so that the sampler's dimensions stay aligned whatever happens (pbrt-v4 §14.2.2).
Pcg32 trackingRng(Sampler& sampler) {
    const uint64_t a = uint64_t(sampler.get1D() * 0x1p32f), b = uint64_t(sampler.get1D() * 0x1p32f);
    return Pcg32(mix64(a << 32 | b), mix64(b ^ 0x9e3779b97f4a7c15ull));
}

/// exp(−σ·d) per lane.
SampledSpectrum transmittance(const SampledSpectrum& sigma, float d) {
    SampledSpectrum t(sigma.size());
    for (int k = 0; k < sigma.size(); ++k) t[k] = std::exp(-sigma[k] * d);
    return t;
}

/// σ_n = max(σ_maj − σ_t, 0) per lane: the null-collision coefficient.
SampledSpectrum nullCoefficient(const SampledSpectrum& sigmaMaj, const SampledSpectrum& sigmaT) {
    SampledSpectrum n = sigmaMaj - sigmaT;
    for (int k = 0; k < n.size(); ++k) n[k] = std::max(n[k], 0.0f);
    return n;
}

/// Tentative collisions along the majorant segments of `it` (delta/ratio tracking; pbrt-v4
/// §14.2.1, SampleT_maj): free flights with rate σ_maj in lane h, t = −ln(1 − ξ)/σ_maj[h]; a segment
/// whose lane-h majorant is 0 is crossed without collisions. At each collision
/// `collision(t, segment, T_maj)` is called with the majorant transmittance since the previous
/// collision (or the start); it returns false to stop the walk, and then the result is nullopt.
/// Otherwise the result is T_maj from the last collision to the end of the last segment.
template <typename F>
std::optional<SampledSpectrum> sampleCollisions(MajorantIterator* it, int h, int lanes, Pcg32& rng, F&& collision) {
    SampledSpectrum tMaj(lanes, 1.0f);
    while (const std::optional<MajorantSegment> seg = it->next()) {
        const float sMaj = seg->sigmaMaj[h];
        float t = seg->tMin;
        if (!(sMaj > 0)) {  // nothing to collide with in the sampling lane
            tMaj *= transmittance(seg->sigmaMaj, seg->tMax - t);
            continue;
        }
        for (;;) {
            const float dt = -std::log(1.0f - rng.uniform()) / sMaj;  // free flight ∝ σ_maj e^{−σ_maj t}
            if (t + dt >= seg->tMax) {
                tMaj *= transmittance(seg->sigmaMaj, seg->tMax - t);
                break;
            }
            t += dt;
            tMaj *= transmittance(seg->sigmaMaj, dt);
            if (!collision(t, *seg, tMaj)) return std::nullopt;
            tMaj = SampledSpectrum(lanes, 1.0f);
        }
    }
    return tMaj;
}

class VolPathIntegrator final : public Integrator {
public:
    VolPathIntegrator(std::string type, const PathParams& p, bool spectralMIS)
        : Integrator(std::move(type), p.maxDepth), params_(p), spectralMIS_(spectralMIS),
          maxDepth_(p.maxDepth < 0 ? std::numeric_limits<int>::max() : p.maxDepth) {}
    bool rendersMedia() const override { return true; }

    SampledSpectrum Li(const Scene& scene, const Ray& cameraRay, SampledWavelengths& wl, Sampler& sampler, Arena& arena,
                       PathStats& stats) const override {
        const int n = wl.size();
        PathState<false> ps{SampledSpectrum(n, 0.0f), SampledSpectrum(n, 1.0f), SampledSpectrum(n, 1.0f), SampledSpectrum(n, 1.0f)};
        walk(scene, cameraRay, ps, wl, sampler, arena, stats);
        return ps.L;
    }
    bool hasPolarizedForm() const override { return true; }
    void LiStokes(const Scene& scene, const Ray& cameraRay, SampledWavelengths& wl, Sampler& sampler, Arena& arena, PathStats& stats,
                  StokesEstimate& est) const override {
        const int n = wl.size();
        const vec3 basis = est.rows > 1 ? est.basis : stokesBasis(-glm::normalize(cameraRay.d));
        PathState<true> ps{StokesVector(n), StokesThroughput(est.rows, n, basis), SampledSpectrum(n, 1.0f), SampledSpectrum(n, 1.0f)};
        walk(scene, cameraRay, ps, wl, sampler, arena, stats);
        for (int k = 0; k < est.rows; ++k) est.S.s[k] += ps.L.s[k];
    }

private:
    /// The path from the camera ray (Li's loop; the file comment).
    template <bool P>
    void walk(const Scene& scene, const Ray& cameraRay, PathState<P>& ps, SampledWavelengths& wl, Sampler& sampler, Arena& arena,
              PathStats& stats) const;
    /// The denominator of a contribution from the pdf ratios r (see the file comment).
    float reduce(const SampledSpectrum& r, int h, const SampledWavelengths& wl) const {
        return spectralMIS_ && !wl.secondaryTerminated() ? r.average() : r[h];
    }
    /// Delta tracking from ray.o to tHit; on a real scattering event samples the phase function and
    /// NEE, updates `ray` and returns true.
    template <bool P>
    bool trackMedium(const Scene& scene, Ray& ray, float tHit, int h, PathState<P>& ps, SampledWavelengths& wl, Sampler& sampler,
                     Pcg32& rng, Arena& arena, PathStats& stats) const;
    /// A medium scattering at p: next-event estimation and phase sampling (returns false when the
    /// path ends there).
    template <bool P>
    bool scatterInMedium(const Scene& scene, const vec3& p, Ray& ray, int h, PathState<P>& ps, SampledWavelengths& wl,
                         Sampler& sampler, Pcg32& rng, Arena& arena, PathStats& stats) const;
    /// Emission reached by a BSDF/phase-sampled ray: infinite lights (si = nullptr) or the area
    /// light at si.
    template <bool P>
    void addEmission(const Scene& scene, const Ray& ray, const SurfaceInteraction* si, int h, PathState<P>& ps,
                     const SampledWavelengths& wl) const;
    /// A volumelight's emission at a collision at p (any kind: real or null), sampled with density
    /// T_maj σ_maj in lane h: β T_maj j / (T_maj[h] σ_maj[h]), weighted over the lanes as the
    /// unidirectional strategy (pbrt-v4 §14.2.2, emission at every majorant collision; media/
    /// volume_light.h for j). Volume emitters are reached only this way (no next-event estimation).
    /// Polarized: the emission is unpolarized (Mitsuba 3's emitters).
    template <bool P>
    void addMediumEmission(const vec3& p, const MajorantSegment& seg, const SampledSpectrum& tm, int h, PathState<P>& ps,
                           const SampledWavelengths& wl) const {
        const Volume* j = ps.medium->emission();
        if (!j || (params_.hideEmitters && ps.depth == 0)) return;
        const float pdf = tm[h] * seg.sigmaMaj[h];
        const SampledSpectrum rE = ps.rU * tm * seg.sigmaMaj / pdf;
        if (!(pdf > 0) || rE.isBlack()) return;
        if constexpr (P) ps.beta.addUnpolarized(tm * j->eval(p, wl) / pdf, 1.0f / reduce(rE, h, wl), ps.L);
        else ps.L += ps.beta * tm * j->eval(p, wl) / pdf / reduce(rE, h, wl);
    }
    /// Russian roulette after a real scattering event (pbrt-v4 §14.2.3), on the MIS-weighted
    /// throughput with radiance scaling undone; u is drawn at every event. False: the path ends.
    template <bool P>
    bool survivesRoulette(PathState<P>& ps, int h, const SampledWavelengths& wl, float u) const {
        if (ps.depth < params_.rrDepth) return true;
        float m;
        if constexpr (P) m = (ps.beta.intensity() * ps.etaScale).maxValue();  // unpolarized weight (Mitsuba 3)
        else m = (ps.beta * ps.etaScale).maxValue();
        const float q = rouletteSurvival(m / reduce(ps.rU, h, wl), u);
        if (q == 0.0f) return false;
        if constexpr (P) ps.beta *= 1.0f / q;
        else ps.beta /= q;
        return true;
    }
    /// Surface scattering; returns false when the path ends.
    template <bool P>
    bool scatterAtSurface(const Scene& scene, const SurfaceInteraction& si, Ray& ray, int h, PathState<P>& ps,
                          SampledWavelengths& wl, Sampler& sampler, Pcg32& rng, Arena& arena, PathStats& stats) const;

    /// Next-event estimation's contribution of the light sample s taken at p — the surface point
    /// si, or (si = nullptr) a point in ps.medium — added to ps.L: its shadow ray's transmittance
    /// and the MIS ratios. Polarized: `v` is the vertex's Mueller matrix towards the light and the
    /// rows' basis its output basis.
    template <bool P>
    void addLight(const Scene& scene, const vec3& p, const SurfaceInteraction* si, const VertexLightSample& s, const VertexMueller* v,
                  int h, PathState<P>& ps, const SampledWavelengths& wl, Pcg32& rng, Arena& arena, PathStats& stats) const;
    /// Transmittance from `o` towards `target` (or to infinity along `dir`), by ratio tracking
    /// through media and pass-through surfaces; 0 when an opaque surface blocks. Updates the
    /// strategies' pdf ratios rU, rL along the way. T: SampledSpectrum, or a ShadowMueller.
    template <typename Transmittance>
    Transmittance shadowTransmittance(const Scene& scene, vec3 o, const vec3& dir, float dist, const Medium* medium, int h,
                                      SampledSpectrum& rU, SampledSpectrum& rL, const SampledWavelengths& wl, Pcg32& rng,
                                      Arena& arena, PathStats& stats) const;

    PathParams params_;
    bool spectralMIS_;
    int maxDepth_;
};

template <bool P>
void VolPathIntegrator::walk(const Scene& scene, const Ray& cameraRay, PathState<P>& ps, SampledWavelengths& wl, Sampler& sampler,
                             Arena& arena, PathStats& stats) const {
    const int n = wl.size();
    ps.medium = scene.description().camera.medium.get();
    const float uLane = sampler.get1D();
    const int h = wl.isRGB() ? std::min(int(uLane * n), n - 1) : 0;
    Pcg32 rng = trackingRng(sampler);
    Ray ray(cameraRay.o, glm::normalize(cameraRay.d));
    ++stats.paths;

    // A path crossing more than kMaxCrossings boundaries in a row without scattering (stacked null
    // surfaces) is ended rather than followed forever.
    constexpr int kMaxCrossings = 1000;
    for (int crossings = 0, lastDepth = 0; ps.depth < maxDepth_; ++crossings) {
        if (ps.depth != lastDepth) crossings = 0, lastDepth = ps.depth;
        if (crossings > kMaxCrossings) break;
        ++stats.rays;
        const std::optional<SurfaceInteraction> hit = scene.intersect(ray);
        const float tHit = hit ? hit->t : std::numeric_limits<float>::infinity();
        if (ps.medium && trackMedium(scene, ray, tHit, h, ps, wl, sampler, rng, arena, stats)) {
            arena.reset();
            continue;  // scattered in the medium: ray is the new direction
        }
        if (ps.terminated || ps.beta.isBlack() || ps.rU.isBlack()) break;
        if (!hit) {
            addEmission(scene, ray, nullptr, h, ps, wl);
            break;
        }
        addEmission(scene, ray, &*hit, h, ps, wl);
        if (!scatterAtSurface(scene, *hit, ray, h, ps, wl, sampler, rng, arena, stats)) break;
        arena.reset();
    }
}

template <bool P>
bool VolPathIntegrator::trackMedium(const Scene& scene, Ray& ray, float tHit, int h, PathState<P>& ps, SampledWavelengths& wl,
                                    Sampler& sampler, Pcg32& rng, Arena& arena, PathStats& stats) const {
    bool scattered = false;
    const std::optional<SampledSpectrum> tMaj = sampleCollisions(
        ps.medium->majorants(ray, tHit, wl, arena), h, wl.size(), rng,
        [&](float t, const MajorantSegment& seg, const SampledSpectrum& tm) {
            const float sMaj = seg.sigmaMaj[h];
            const vec3 p = ray.at(t);
            const MediumCoefficients c = ps.medium->coefficients(p, wl);
            addMediumEmission(p, seg, tm, h, ps, wl);
            if (rng.uniform() < c.sigmaT[h] / sMaj) {
                // A real collision, pdf T_maj σ_t in lane h: scattering with the path's weight times
                // T_maj σ_s (the albedo; Mitsuba 3 volpath.cpp, weight_scatter · σ_s).
                const float pdf = tm[h] * c.sigmaT[h];
                ps.beta *= tm * c.sigmaS / pdf;
                ps.rU *= tm * c.sigmaT / pdf;
                if (ps.beta.isBlack() || ps.rU.isBlack()) return ps.terminated = true, false;
                scattered = scatterInMedium(scene, p, ray, h, ps, wl, sampler, rng, arena, stats);
                return false;
            }
            // Null scattering: pdf T_maj σ_n in lane h; the light strategy's ratio uses σ_maj.
            const SampledSpectrum sigmaN = nullCoefficient(seg.sigmaMaj, c.sigmaT);
            const float pdf = tm[h] * sigmaN[h];
            if (!(pdf > 0)) return ps.terminated = true, false;
            ps.beta *= tm * sigmaN / pdf;
            ps.rU *= tm * sigmaN / pdf;
            ps.rL *= tm * seg.sigmaMaj / pdf;
            if (ps.beta.isBlack() || ps.rU.isBlack()) return ps.terminated = true, false;
            return true;
        });
    if (!tMaj) return scattered;
    // Reached the surface (or left the medium's extent): pdf of no collision, T_maj in lane h.
    const float pdf = (*tMaj)[h];
    if (!(pdf > 0)) return ps.terminated = true, false;
    ps.beta *= *tMaj / pdf;
    ps.rU *= *tMaj / pdf;
    ps.rL *= *tMaj / pdf;
    return false;
}

template <bool P>
bool VolPathIntegrator::scatterInMedium(const Scene& scene, const vec3& p, Ray& ray, int h, PathState<P>& ps,
                                        SampledWavelengths& wl, Sampler& sampler, Pcg32& rng, Arena& arena, PathStats& stats) const {
    // This event is scattering number depth (counted before the check, Mitsuba 3 volpath.cpp
    // `depth += 1; active &= depth < max_depth`), so next-event estimation here is allowed whenever
    // the path goes on, like a surface's at depth + 1 < max_depth before its own increment.
    if (++ps.depth >= maxDepth_) return ps.terminated = true, false;
    const PhaseFunction& phase = ps.medium->phase();
    const vec3 wo = -ray.d;
    if constexpr (P) ps.beta.changeBasis(wo, stokesBasis(wo));  // the phase matrices' output basis
    if (!scene.lights().empty()) {  // drawn either way: the sample stream stays aligned
        const vec2 uL = sampler.get2D();
        if (ps.medium->sampleEmitters())
            if (const auto s = sampleLightInMedium(scene, p, phase, wo, uL, wl)) {
                if constexpr (P) {
                    const VertexMueller v = phaseMueller(phase, p, wo, s->ls.wi, wl.size());
                    addLight(scene, p, nullptr, *s, &v, h, ps, wl, rng, arena, stats);
                } else {
                    addLight(scene, p, nullptr, *s, nullptr, h, ps, wl, rng, arena, stats);
                }
            }
    }
    const std::optional<PhaseSample> s = phase.sample(p, wo, sampler.get2D());
    if (!s || !(s->pdf > 0)) return ps.terminated = true, false;
    if constexpr (P) ps.beta.apply(phase.evalMueller(p, wo, s->wi, wl.size()) * (1.0f / s->pdf), stokesBasis(-s->wi));
    else ps.beta *= s->weight();
    ps.rL = ps.rU / s->pdf;
    ps.specularBounce = false;
    ps.prevP = p;
    ray = Ray(p, s->wi);
    if (!survivesRoulette(ps, h, wl, sampler.get1D())) return ps.terminated = true, false;
    return true;
}

template <bool P>
void VolPathIntegrator::addEmission(const Scene& scene, const Ray& ray, const SurfaceInteraction* si, int h, PathState<P>& ps,
                                    const SampledWavelengths& wl) const {
    if (params_.hideEmitters && ps.depth == 0) return;
    forEachEmission(scene, si, ray.d, wl, [&](const Light& light, const SampledSpectrum& Le) {
        if (Le.isBlack()) return;
        float d = 0;
        if (ps.depth == 0 || ps.specularBounce) {
            d = reduce(ps.rU, h, wl);
        } else {
            const SampledSpectrum rL = ps.rL * lightSamplingPdf(scene, light, ps.prevP, ray.d, si);
            d = reduce(ps.rU + rL, h, wl);
        }
        if constexpr (P) ps.beta.addUnpolarized(Le, 1.0f / d, ps.L);  // emitters are unpolarized
        else ps.L += ps.beta * Le / d;
    });
}

template <bool P>
bool VolPathIntegrator::scatterAtSurface(const Scene& scene, const SurfaceInteraction& si, Ray& ray, int h, PathState<P>& ps,
                                         SampledWavelengths& wl, Sampler& sampler, Pcg32& rng, Arena& arena,
                                         PathStats& stats) const {
    const ShadingPoint sp = shadingPointAt(si);
    const Frame& frame = sp.shading;
    const BSDF* bsdf = si.material->getBSDF(sp, wl, arena);
    const vec3 wo = frame.toLocal(si.wo);
    if (passesUnchanged<P>(bsdf, wo)) {  // a boundary only: not a bounce (Mitsuba 3 volpath)
        ps.medium = mediumAfter(scene, si, ray.d, ps.medium);
        ray = si.spawnRay(ray.d);
        return true;
    }
    if constexpr (P) ps.beta.changeBasis(frame.toWorld(wo), frame.toWorld(stokesBasis(wo)));  // the BSDF's output basis
    if (!scene.lights().empty()) {  // drawn either way: the sample stream stays aligned
        const vec2 uL = sampler.get2D();
        if (bsdf->hasNonSpecular() && ps.depth + 1 < maxDepth_)
            if (const auto s = sampleLightAtSurface(scene, si.p, si.ng, frame, *bsdf, wo, uL, wl, params_.strictNormals)) {
                if constexpr (P) {
                    const VertexMueller v = surfaceMueller(*bsdf, frame, wo, frame.toLocal(s->ls.wi));
                    addLight(scene, si.p, &si, *s, &v, h, ps, wl, rng, arena, stats);
                } else {
                    addLight(scene, si.p, &si, *s, nullptr, h, ps, wl, rng, arena, stats);
                }
            }
    }
    const float uc = sampler.get1D();
    const vec2 u = sampler.get2D();
    std::optional<BSDFSample> bs;
    std::optional<PolarizedBSDFSample> pbs;
    if constexpr (P) {
        pbs = bsdf->sampleMueller(wo, uc, u, TransportMode::Radiance);
        if (pbs) bs = pbs->s;
    } else {
        bs = bsdf->sample(wo, uc, u, TransportMode::Radiance);
    }
    if (!bs || bs->pdf <= 0 || bs->f.isBlack()) return false;
    const bool passThrough = bs->isNull();
    const vec3 wiWorld = passThrough ? ray.d : glm::normalize(frame.toWorld(bs->wi));
    if (params_.strictNormals && !passThrough && !sidesAgree(wiWorld, si.ng, bs->wi.z)) return false;
    if constexpr (P) ps.beta.apply(pbs->M * (std::abs(bs->wi.z) / bs->pdf), frame.toWorld(stokesBasis(-bs->wi)));
    else ps.beta *= bs->f * (std::abs(bs->wi.z) / bs->pdf);
    if (!passThrough) {  // a real bounce (the null lobe of a mask is a boundary crossing)
        ++ps.depth;
        ps.specularBounce = bs->isSpecular();
        ps.rL = ps.rU / bs->pdf;
        ps.prevP = si.p;
        if (bs->isTransmission()) ps.etaScale *= sqr(bs->eta);
    }
    ps.medium = mediumAfter(scene, si, wiWorld, ps.medium);
    ray = si.spawnRay(wiWorld);
    if (ps.beta.isBlack() || ps.beta.hasNonFinite()) return false;
    const float uRR = sampler.get1D();
    return passThrough || survivesRoulette(ps, h, wl, uRR);
}

template <bool P>
void VolPathIntegrator::addLight(const Scene& scene, const vec3& p, const SurfaceInteraction* si, const VertexLightSample& s,
                                 const VertexMueller* v, int h, PathState<P>& ps, const SampledWavelengths& wl, Pcg32& rng,
                                 Arena& arena, PathStats& stats) const {
    const LightSample& ls = s.ls;
    // The shadow ray: from the surface (offset to the light's side; leaving a medium transition
    // towards the light may enter the other side's medium) or the medium point, to the light point
    // (offset off an area light) or to infinity.
    const vec3 o = si ? offsetRayOrigin(p, si->ng, ls.wi) : p;
    const Medium* start = si ? mediumAfter(scene, *si, ls.wi, ps.medium) : ps.medium;
    float dist = std::numeric_limits<float>::infinity();
    vec3 dir = ls.wi;
    if (!ls.infinite) {
        const vec3 target = glm::dot(ls.nLight, ls.nLight) > 0 ? offsetRayOrigin(ls.pLight, ls.nLight, -ls.wi) : ls.pLight;
        const vec3 d = target - o;
        dist = glm::length(d) * (1.0f - 1e-4f);
        if (!(dist > 0)) return;
        dir = d / glm::length(d);
    }
    SampledSpectrum rL = ps.rU * s.lightPdf, rU = ps.rU * s.scatterPdf;
    using Transmittance = std::conditional_t<P, ShadowMueller, SampledSpectrum>;
    const Transmittance T = shadowTransmittance<Transmittance>(scene, o, dir, dist, start, h, rU, rL, wl, rng, arena, stats);
    if (T.isBlack()) return;
    const float d = s.light->isDelta() ? reduce(rL, h, wl) : reduce(rL + rU, h, wl);
    if constexpr (P) {
        addLightThrough(ps.beta, *v, T, ls.L, 1.0f / d, ps.L);
    } else {
        (void)v;
        const SampledSpectrum contrib = ps.beta * s.f * T * ls.L;
        ps.L += contrib / d;
    }
}

template <typename Transmittance>
Transmittance VolPathIntegrator::shadowTransmittance(const Scene& scene, vec3 o, const vec3& dir, float dist, const Medium* medium,
                                                     int h, SampledSpectrum& rU, SampledSpectrum& rL, const SampledWavelengths& wl,
                                                     Pcg32& rng, Arena& arena, PathStats& stats) const {
    constexpr bool P = !std::is_same_v<Transmittance, SampledSpectrum>;
    auto blocked = [&] {
        if constexpr (P) return ShadowMueller::zero(wl.size(), dir);
        else return SampledSpectrum(wl.size(), 0.0f);
    };
    Transmittance T = [&] {
        if constexpr (P) return ShadowMueller(wl.size(), dir);
        else return SampledSpectrum(wl.size(), 1.0f);
    }();
    for (int crossings = 0; crossings < 1000; ++crossings) {
        ++stats.rays;
        const std::optional<SurfaceInteraction> hit = scene.intersect(Ray(o, dir, dist));
        if (hit && !crossSurface(*hit, dir, wl, arena, T)) return blocked();
        const float tEnd = hit ? hit->t : dist;
        if (medium) {
            // Ratio tracking (Novák et al. 2014), collisions ∝ σ_maj in lane h.
            const std::optional<SampledSpectrum> tMaj = sampleCollisions(
                medium->majorants(Ray(o, dir), tEnd, wl, arena), h, wl.size(), rng,
                [&](float t, const MajorantSegment& seg, const SampledSpectrum& tm) {
                    const MediumCoefficients c = medium->coefficients(o + t * dir, wl);
                    const SampledSpectrum sigmaN = nullCoefficient(seg.sigmaMaj, c.sigmaT);
                    const float pdf = tm[h] * seg.sigmaMaj[h];
                    T *= tm * sigmaN / pdf;
                    rL *= tm * seg.sigmaMaj / pdf;
                    rU *= tm * sigmaN / pdf;
                    // Russian roulette on a small ratio-tracking weight (pbrt-v4 §14.2.3).
                    const float tr = T.maxValue() / reduce(rL + rU, h, wl);
                    if (tr < 0.05f) {
                        if (rng.uniform() < 0.75f) return false;
                        T /= 0.25f;
                    }
                    return !T.isBlack();
                });
            if (!tMaj) return blocked();
            const float pdf = (*tMaj)[h];
            if (!(pdf > 0)) return blocked();
            T *= *tMaj / pdf;
            rL *= *tMaj / pdf;
            rU *= *tMaj / pdf;
        }
        if (!hit) return T;
        medium = mediumAfter(scene, *hit, dir, medium);
        o = hit->spawnRay(dir).o;
        dist -= hit->t;
        if (!(dist > 0)) return T;
    }
    return T;
}

std::shared_ptr<Integrator> createVolPath(const Properties& p) {
    return std::make_shared<VolPathIntegrator>(p.type(), readPathParams(p), false);
}
std::shared_ptr<Integrator> createVolPathMIS(const Properties& p) {
    return std::make_shared<VolPathIntegrator>(p.type(), readPathParams(p), true);
}

}  // namespace

IRIS_REGISTER(IntegratorRegistry, "volpath", createVolPath);
IRIS_REGISTER(IntegratorRegistry, "volpathmis", createVolPathMIS);

}  // namespace iris
