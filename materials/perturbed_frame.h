// Shading-frame perturbations of the `normalmap` and `bumpmap` wrapper materials (Mitsuba 3
// v3.7, src/bsdfs/perturbed.h — the CRTP base `PerturbedBSDF` both plugins share — and
// normalmap_helpers.h), and the creation of the material they wrap.
//
// The integrator keeps the unperturbed shading frame (Material::shadingFrame is not overridden);
// the perturbation lives in the BSDF returned by getBSDF (PerturbedBSDF below), which, as
// Mitsuba's, needs the direction towards the viewer to choose the frame (flip_invalid_normals).
#pragma once

#include <set>
#include <string>
#include <vector>

#include "core/frame.h"
#include "core/registry.h"
#include "materials/material.h"
#include "materials/mueller_frames.h"
#include "materials/nested_materials.h"

namespace iris {

/// Mitsuba 3's options of both wrappers (PerturbedBSDF's constructor), both on by default;
/// Mitsuba 0.6's normalmap/bumpmap (2014) had neither, so the upgrade pass turns them off in a
/// version 0.x scene (render/loader/scene_upgrade.h).
struct PerturbOptions {
    bool flipInvalidNormals = true;    // flip_invalid_normals
    bool useShadowingFunction = true;  // use_shadowing_function
    static PerturbOptions read(const Properties& p) {
        PerturbOptions o;
        o.flipInvalidNormals = p.getBool("flip_invalid_normals", true);
        o.useShadowingFunction = p.getBool("use_shadowing_function", true);
        return o;
    }
};

/// The perturbed frame relative to the unperturbed one (Mitsuba 3 PerturbedBSDF::frames): the
/// normal is the normalised (unnormalised) perturbation `nLocal` (0, 0, 1 if it has no finite
/// direction); the tangent is the unperturbed tangent (1, 0, 0) Gram–Schmidt-orthogonalised
/// against it, s = normalize(e_x − n n_x) ((0, 1, 0) if n = ±e_x); t = n × s. (Mitsuba 3 before
/// v3.6 used the world-space ∂p/∂u with the local normal here, mitsuba3 pull request #905.)
inline Frame localPerturbedFrame(const vec3& nLocal) {
    const float len2 = glm::dot(nLocal, nLocal);
    const vec3 n = (len2 > 0 && std::isfinite(len2) && isFinite(nLocal)) ? nLocal / std::sqrt(len2) : vec3(0, 0, 1);
    vec3 s = vec3(1, 0, 0) - n * n.x;
    const float s2 = glm::dot(s, s);
    s = s2 > 0 && std::isfinite(s2) ? s / std::sqrt(s2) : vec3(0, 1, 0);
    return Frame(s, glm::cross(n, s), n);
}

/// flip_invalid_normals (Mitsuba 3, after Schüssler et al. 2017, "Microfacet-based Normal Mapping
/// for Robust Monte Carlo Path Tracing", §3): keep the perturbed normal on the side of the
/// direction towards the viewer wo (unperturbed local frame): if wo.z · (wo · n) ≤ 0 the normal
/// is mirrored about the unperturbed one, n → (−n_x, −n_y, n_z).
inline vec3 flipInvalidNormal(const vec3& nLocal, const vec3& wo) {
    return wo.z * glm::dot(wo, nLocal) <= 0 ? vec3(-nLocal.x, -nLocal.y, nLocal.z) : nLocal;
}

/// The microfacet-based shadowing term against the bump terminator (Conty Estevez, Lecocq, Stein
/// 2019, "A Microfacet-Based Shadowing Function to Solve the Bump Terminator Problem", Ray
/// Tracing Gems ch. 12; Mitsuba 3 normalmap_helpers.h eval_shadow_terminator): the perturbed
/// normal n (unperturbed local frame) sets a GGX roughness α² = min(tan²θ_n / 8, 1), and the
/// light direction w is attenuated by Smith's G1 for it (Walter et al. 2007, eq. 34):
/// G = 2 / (1 + sqrt(1 + α² tan²θ_w)).
inline float shadowTerminator(const vec3& n, const vec3& w) {
    const float alpha2 = std::min(0.125f * tan2Theta(n), 1.0f);
    const float t2 = tan2Theta(w);
    if (!std::isfinite(t2)) return 0.0f;  // w in the tangent plane
    return 2.0f / (1.0f + std::sqrt(1.0f + alpha2 * t2));
}

/// The BSDF of a perturbed material (Mitsuba 3 PerturbedBSDF sample/eval/pdf). Directions are in
/// the unperturbed local frame; each call expresses them in the perturbed frame chosen for wo
/// (normal `n` or, with flipping, its mirror image), clears pairs whose wi lies on different
/// sides of the unperturbed and perturbed normals, and evaluates the nested BSDF there. iris's
/// BSDFs exclude the cosine, which the integrator takes in the unperturbed frame: the value is
/// rescaled by |cos θi'| / |cos θi| (Mitsuba's eval includes the cosine of the perturbed frame),
/// and multiplied by shadowTerminator with the options.
class PerturbedBSDF final : public BSDF {
public:
    /// `nested` is evaluated in the frame of `n`, `nestedFlipped` (may equal `nested`) in the
    /// frame of the flipped normal.
    PerturbedBSDF(const BSDF* nested, const BSDF* nestedFlipped, const vec3& n, const PerturbOptions& opt, int nWl)
        : nested_{nested, nestedFlipped}, n_{n, vec3(-n.x, -n.y, n.z)}, opt_(opt), nWl_(nWl) {
        frame_[0] = localPerturbedFrame(n_[0]);
        frame_[1] = localPerturbedFrame(n_[1]);
    }

    SampledSpectrum eval(const vec3& wo, const vec3& wi, TransportMode mode) const override {
        // Not reciprocal (the frame is chosen for wo, the shadowing and the cosine rescaling are of
        // wi): importance transport takes the adjoint f*(wo, wi) = f(wi, wo) (Veach 1997 eq. 3.21).
        if (mode == TransportMode::Importance) return eval(wi, wo, TransportMode::Radiance);
        const int k = choose(wo);
        const vec3 wiP = frame_[k].toLocal(wi);
        if (!(wi.z * wiP.z > 0)) return SampledSpectrum(nWl_);
        return nested_[k]->eval(frame_[k].toLocal(wo), wiP, mode) * factor(k, wi, wiP);
    }
    float pdf(const vec3& wo, const vec3& wi, TransportMode mode) const override {
        const int k = choose(wo);
        const vec3 wiP = frame_[k].toLocal(wi);
        if (!(wi.z * wiP.z > 0)) return 0.0f;
        return nested_[k]->pdf(frame_[k].toLocal(wo), wiP, mode);
    }
    std::optional<BSDFSample> sample(const vec3& wo, float uc, const vec2& u, TransportMode mode) const override {
        const int k = choose(wo);
        auto s = nested_[k]->sample(frame_[k].toLocal(wo), uc, u, mode);
        if (!s) return std::nullopt;
        const vec3 wi = frame_[k].toWorld(s->wi);
        if (!(wi.z * s->wi.z > 0)) return std::nullopt;  // Mitsuba: pdf and weight 0
        if (mode == TransportMode::Importance) {
            // The adjoint f*(wo, wi) = f(wi, wo) (Veach 1997 eq. 3.21): the frame wi would choose
            // and the shadowing of wo. A delta lobe keeps the nested adjoint's coefficient, rescaled
            // to the unperturbed cosine, where wi chooses wo's frame and wo lies on one side of both
            // normals (else the reverse radiance sample does not reach wo and f(wi, wo) = 0).
            if (!s->isSpecular()) {
                s->f = eval(wo, wi, mode);
            } else {
                if (choose(wi) != k || !(wo.z * frame_[k].toLocal(wo).z > 0)) return std::nullopt;
                const float g = opt_.useShadowingFunction ? shadowTerminator(frame_[k].n, wo) : 1.0f;
                s->f *= g * std::abs(s->wi.z) / std::abs(wi.z);
            }
        } else {
            s->f *= factor(k, wi, s->wi);
        }
        s->wi = wi;
        return s;
    }
    uint32_t flags() const override { return nested_[0]->flags() | nested_[1]->flags(); }
    /// Polarized: the nested matrix, computed in the perturbed frame, re-expressed in this frame's
    /// bases (materials/mueller_frames.h; Mitsuba 3's PerturbedBSDF hands it on unrotated,
    /// docs/polarization.md).
    MuellerSpectrum evalMueller(const vec3& wo, const vec3& wi, TransportMode mode) const override {
        const int k = choose(wo);
        const vec3 wiP = frame_[k].toLocal(wi);
        if (!(wi.z * wiP.z > 0)) return MuellerSpectrum::depolarizer(SampledSpectrum(nWl_));
        const MuellerSpectrum M = nested_[k]->evalMueller(frame_[k].toLocal(wo), wiP, mode) * factor(k, wi, wiP);
        return fromNestedFrame(M, frame_[k], false, wi, wo);
    }
    std::optional<PolarizedBSDFSample> sampleMueller(const vec3& wo, float uc, const vec2& u, TransportMode mode) const override {
        const int k = choose(wo);
        auto s = nested_[k]->sampleMueller(frame_[k].toLocal(wo), uc, u, mode);
        if (!s) return std::nullopt;
        const vec3 wi = frame_[k].toWorld(s->s.wi);
        if (!(wi.z * s->s.wi.z > 0)) return std::nullopt;
        const float f = factor(k, wi, s->s.wi);
        s->s.f *= f;
        s->s.wi = wi;
        s->M = fromNestedFrame(s->M * f, frame_[k], false, wi, wo);
        return s;
    }

private:
    int choose(const vec3& wo) const {
        return opt_.flipInvalidNormals && flipInvalidNormal(n_[0], wo) != n_[0] ? 1 : 0;
    }
    /// |cos θi'| / |cos θi| (nonzero: the callers check that both cosines have one sign) times
    /// the shadowing term.
    float factor(int k, const vec3& wi, const vec3& wiP) const {
        const float g = opt_.useShadowingFunction ? shadowTerminator(frame_[k].n, wi) : 1.0f;
        return g * std::abs(wiP.z) / std::abs(wi.z);
    }

    const BSDF* nested_[2];
    vec3 n_[2];
    Frame frame_[2];
    PerturbOptions opt_;
    int nWl_;
};

/// A wrapper material that perturbs the shading normal: subclasses give the (unnormalised)
/// perturbed normal in the unperturbed local frame (Mitsuba 3's `perturbation`).
class PerturbedMaterial : public Material {
public:
    PerturbedMaterial(std::shared_ptr<Material> nested, const PerturbOptions& opt)
        : nested_(std::move(nested)), opt_(opt) {}

    virtual vec3 perturbation(const ShadingPoint& sp) const = 0;

    const BSDF* getBSDF(const ShadingPoint& sp, SampledWavelengths& wl, Arena& arena) const override {
        const vec3 n = perturbation(sp);
        const BSDF* b = nested_->getBSDF(perturbedPoint(sp, n), wl, arena);
        if (!b) return nullptr;
        // A nested perturbation depends on the frame handed to it, so the flipped frame gets its
        // own nested BSDF; for every other material the frame does not matter.
        const BSDF* bf = b;
        if (nested_->perturbsShading()) {
            bf = nested_->getBSDF(perturbedPoint(sp, vec3(-n.x, -n.y, n.z)), wl, arena);
            if (!bf) return nullptr;
        }
        return arena.make<PerturbedBSDF>(b, bf, n, opt_, wl.size());
    }
    bool perturbsShading() const override { return true; }

    /// sp with the perturbed frame of normal nLocal (unperturbed local frame) in world space, as
    /// Mitsuba hands it to the nested BSDF (∂p/∂u, ∂p/∂v and the geometric normal unchanged).
    static ShadingPoint perturbedPoint(const ShadingPoint& sp, const vec3& nLocal) {
        const Frame l = localPerturbedFrame(nLocal);
        ShadingPoint q = sp;
        q.shading = Frame(sp.shading.toWorld(l.s), sp.shading.toWorld(l.t), sp.shading.toWorld(l.n));
        return q;
    }

    const PerturbOptions& options() const { return opt_; }

private:
    std::shared_ptr<Material> nested_;
    PerturbOptions opt_;
};

}  // namespace iris
