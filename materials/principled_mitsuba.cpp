// Mitsuba 3's `principled` BSDF and `principledthin` (Mitsuba 3, src/bsdfs/principled.cpp,
// principledthin.cpp, principledhelpers.h), written from their definitions; both are based on
// [B12] Burley 2012 ("Physically-Based Shading at Disney") and [B15] Burley 2015 ("Extending the
// Disney BRDF to a BSDF with Integrated Subsurface Scattering"). iris's own Disney 2012 BRDF
// (materials/principled.cpp) stays available as `disney` (a version 0.x file's `principled`, renamed by the
// upgrade pass, render/loader/scene_upgrade.h).
// docs/materials_principled_cloth.md §1b lists where Mitsuba's definitions differ from Burley's.
//
// Notation: v = wo (towards the viewer, Mitsuba's si.wi), l = wi (towards the light, Mitsuba's
// wo); iris's eval is f without the cosine, Mitsuba's eval is f·|cosθl|.
//
// principled (m = metallic, st = spec_trans, brdf = (1 − m)(1 − st), bsdf = (1 − m) st; front = v.z > 0):
//   specular reflection  F_p D G / (4 |cosθv cosθl|), D, G: anisotropic GGX, separable Smith
//     F_p (front) = (1 − m)(1 − spec_tint) F_dielectric(η) + m Schlick(base_color)
//                   + (1 − m) spec_tint Schlick(Ctint R0(η)),  R0(η) = ((η − 1)/(η + 1))²
//     F_p (back)  = bsdf F_dielectric(η)
//   specular transmission sqrt(base_color) bsdf (1 − F) D G |v·h||l·h| / (|cosθv cosθl| (v·h + η' l·h)²)
//                   (Walter et al. 2007 eq. 21; importance transport: the adjoint f(l, v), Veach eq. 3.21)
//   clearcoat (front)    0.25 clearcoat F_cc D_GTR1 G_cc   — no 1/(4 cosθv cosθl) (Mitsuba)
//   diffuse (front)      brdf base_color/π mix(f_d + f_retro, f_ss, flatness)   ([B15] eqs. 4–5)
//   sheen (front, brdf > 0) sheen (1 − m) F_H mix(1, Ctint, sheen_tint)
// principledthin (symmetric: both directions are mirrored so that v.z > 0; dt = diff_trans/2):
//   specular reflection  st F_thin D G / (4 cosθv |cosθl|), F_thin = mix(F_dielectric, Schlick(Ctint R0), spec_tint)
//   specular transmission st base_color (1 − F) D' G' / (4 cosθv |cosθl|) with l mirrored up for the
//                         half vector and α' from the roughness (0.65 η − 0.35) roughness ([B15] Fig. 15)
//   diffuse reflection   (1 − st)(1 − dt) [base_color/π mix(f_d + f_retro, f_ss, flatness) + sheen F_H Csheen]
//   diffuse transmission (1 − st) dt base_color/π
// Sampling follows Mitsuba's lobe choice (one-sample MIS with the stated probabilities, pdf = Σ p_i pdf_i);
// see the pdf functions for the probabilities. Both are consistent: in `principled` the front-side
// probabilities of reflection and transmission add up to the constant main_specular_sampling_rate
// and are split by F(v·m) of the sampled microfacet, as in a rough dielectric.
#include <algorithm>

#include "core/registry.h"
#include "core/sampling.h"
#include "materials/fresnel.h"
#include "materials/material.h"
#include "materials/microfacet.h"
#include "materials/principled.h"
#include "materials/principled_terms.h"
#include "materials/textures/texture_params.h"
#include "spectral/ior_params.h"

namespace iris {
namespace {

using principled::schlickWeight;
using principled::schlickWeightMitsuba;

/// Ctint = base / lum (1 where lum = 0) ([B12] §5, Mitsuba principledhelpers.h).
SampledSpectrum tintColour(const SampledSpectrum& base, float lum) {
    return lum > 0 ? base / lum : SampledSpectrum(base.size(), 1.0f);
}

/// Schlick with a spectral F0 and Mitsuba's weight (principled_terms.h): F0 + (1 − F0) w.
SampledSpectrum schlickSpectrum(const SampledSpectrum& f0, float w) { return f0 + (1.0f - f0) * w; }

/// The diffuse lobe shared by both plugins: f_d + f_retro, blended with the Hanrahan–Krueger
/// subsurface approximation by `flatness` ([B12] §5.3, [B15] eqs. 4–5; F_ss90 = R_R/2 = roughness cos²θd).
float diffuseLobe(float cosL, float cosV, float cosD, float roughness, float flatness) {
    const float base = principled::burley2015DiffuseFactor(cosL, cosV, cosD, roughness);
    if (!(flatness > 0)) return base;
    return lerp(flatness, base, principled::subsurfaceFactor(cosL, cosV, cosD, roughness));
}

struct PrincipledM3Params {
    float roughness, anisotropic, metallic, specTrans, specTint, sheen, sheenTint, flatness, clearcoat, clearcoatGloss;
};

struct PrincipledM3Config {
    float eta = 1.5f;
    float specRate = 1.0f, clearcoatRate = 1.0f, diffuseRate = 1.0f;
    bool hasSpecTrans = false, hasClearcoat = false;
};

class PrincipledM3BSDF final : public BSDF {
public:
    PrincipledM3BSDF(const SampledSpectrum& base, float lum, const PrincipledM3Params& p, const PrincipledM3Config& c)
        : p_(p), c_(c), base_(base) {
        ctint_ = tintColour(base, lum);
        brdf_ = (1.0f - p.metallic) * (1.0f - p.specTrans);
        bsdf_ = c.hasSpecTrans ? (1.0f - p.metallic) * p.specTrans : 0.0f;
        const vec2 a = principled::anisotropicAlphas(p.roughness, p.anisotropic);
        spec_ = MicrofacetDistribution(MicrofacetType::GGX, a.x, a.y, true, ShadowingModel::SmithSeparable);
        coat_ = MicrofacetDistribution(MicrofacetType::GGX, 0.25f, 0.25f, false, ShadowingModel::SmithSeparable);
        coatAlpha_ = principled::clearcoatAlpha(p.clearcoatGloss);
        sqrtBase_ = sqrt(base);
        // Tinted Schlick F0 of the dielectric part, Ctint R0(η_it); R0(1/η) = R0(η), so one for both sides.
        tintF0_ = ctint_ * schlickF0FromEta(c.eta);
    }

    SampledSpectrum eval(const vec3& wo, const vec3& wi, TransportMode mode) const override {
        // The adjoint f*(wo, wi) = f(wi, wo) (Veach 1997 eq. 3.21; the front/back Fresnel terms
        // make the lobes non-reciprocal, so no per-lobe factor would do).
        if (mode == TransportMode::Importance) return eval(wi, wo, TransportMode::Radiance);
        const int n = base_.size();
        SampledSpectrum f(n);
        Geometry g;
        if (!geometry(wo, wi, &g)) return f;
        const float cv = std::abs(wo.z), cl = std::abs(wi.z);
        const float D = spec_.D(g.h), G = spec_.G(wi, wo, g.h);
        const float m = p_.metallic;
        if (g.reflect && g.compatReflect && g.F > 0) {
            SampledSpectrum Fp(n);
            if (g.front) {
                const float w = schlickWeightMitsuba(g.dv, c_.eta);
                Fp = SampledSpectrum(n, (1.0f - m) * (1.0f - p_.specTint) * g.F);
                if (m > 0) Fp += schlickSpectrum(base_, w) * m;
                if (p_.specTint > 0) Fp += schlickSpectrum(tintF0_, w) * ((1.0f - m) * p_.specTint);
            } else {
                Fp = SampledSpectrum(n, bsdf_ * g.F);
            }
            f += Fp * (D * G / (4.0f * cv * cl));
        }
        if (bsdf_ > 0 && g.refract && g.compatRefract && g.F < 1) {
            // Walter et al. 2007 eq. 21 with the index on v's side 1 and η' = etaPath on l's side.
            const float t = (1.0f - g.F) * D * G * std::abs(g.dv * g.dl) / (cv * cl * sqr(g.dv + g.etaPath * g.dl));
            f += sqrtBase_ * (bsdf_ * t);
        }
        if (!(g.front && g.reflect)) return f;
        if (c_.hasClearcoat && p_.clearcoat > 0 && g.compatReflect) {
            // Mitsuba 3: f = 0.25 clearcoat F_cc D_cc G_cc (its eval returns that times |cosθl|);
            // Burley's [B12] divides by 4 cosθv cosθl.
            const float fcc = 0.04f + 0.96f * schlickWeightMitsuba(g.dv, c_.eta);
            const float dcc = principled::gtr1D(g.h.z, coatAlpha_);
            const float gcc = coat_.G(wi, wo, g.h);
            f += SampledSpectrum(n, 0.25f * p_.clearcoat * fcc * dcc * gcc);
        }
        if (brdf_ > 0) {
            const float cosD = glm::dot(g.h, wi);
            f += base_ * (brdf_ * diffuseLobe(cl, cv, cosD, p_.roughness, p_.flatness) * kInvPi);
            if (p_.sheen > 0 && m < 1) {
                const float fd = schlickWeight(std::abs(cosD));
                const float k = p_.sheen * (1.0f - m) * fd;
                if (p_.sheenTint > 0)
                    f += lerp(p_.sheenTint, SampledSpectrum(n, 1.0f), ctint_) * k;
                else
                    f += SampledSpectrum(n, k);
            }
        }
        return f;
    }

    std::optional<BSDFSample> sample(const vec3& wo, float uc, const vec2& u, TransportMode mode) const override {
        if (wo.z == 0) return std::nullopt;
        const bool front = wo.z > 0;
        if (!front && !(bsdf_ > 0)) return std::nullopt;
        // The main lobe's microfacet first: its Fresnel splits reflection from transmission.
        const vec3 m = spec_.sampleNormal(wo, u);
        const FresnelDielectricResult fr = fresnelDielectricFull(glm::dot(wo, m), c_.eta);
        const Probabilities pr = probabilities(front, fr.R);
        BSDFSample s;
        const vec3 sm = front ? m : -m;  // the microfacet normal on v's side
        if (uc < pr.diffuse) {
            s.wi = sampleCosineHemisphere(u);
            s.flags = kBSDFReflection | kBSDFDiffuse;
        } else if (uc < pr.diffuse + pr.clearcoat) {
            const vec3 mc = principled::sampleGTR1(u, coatAlpha_);
            s.wi = reflect(wo, mc);
            if (!(glm::dot(wo, mc) > 0 && glm::dot(s.wi, mc) > 0)) return std::nullopt;
            s.flags = kBSDFReflection | kBSDFGlossy;
        } else if (uc < pr.diffuse + pr.clearcoat + pr.specTrans) {
            s.wi = glm::normalize(refract(wo, m, fr.cosThetaT, fr.etaTI));
            if (!(glm::dot(wo, sm) > 0 && glm::dot(s.wi, sm) < 0) || s.wi.z * wo.z >= 0) return std::nullopt;
            s.flags = kBSDFTransmission | kBSDFGlossy;
            s.eta = fr.etaIT;
        } else {
            s.wi = reflect(wo, m);
            if (!(glm::dot(wo, sm) > 0 && glm::dot(s.wi, sm) > 0)) return std::nullopt;
            s.flags = kBSDFReflection | kBSDFGlossy;
        }
        if (s.wi.z * wo.z == 0) return std::nullopt;
        if (!s.isTransmission() && s.wi.z * wo.z < 0) return std::nullopt;
        s.pdf = pdf(wo, s.wi, mode);
        if (!(s.pdf > 0)) return std::nullopt;
        s.f = eval(wo, s.wi, mode);
        return s;
    }

    float pdf(const vec3& wo, const vec3& wi, TransportMode) const override {
        Geometry g;
        if (!geometry(wo, wi, &g)) return 0.0f;
        // Without transmission nothing is sampled from inside (Mitsuba's pdf is not 0 there, but
        // its eval is, so this changes no estimate).
        if (!g.front && !(bsdf_ > 0)) return 0.0f;
        const Probabilities pr = probabilities(g.front, g.F);
        // dωh/dωl: reflection 1/(4|l·h|) (Walter et al. 2007 eq. 14), refraction η'²|l·h|/(v·h + η' l·h)² (eq. 17).
        const float jac = g.reflect ? 1.0f / (4.0f * std::abs(g.dl))
                                    : sqr(g.etaPath) * std::abs(g.dl) / sqr(g.dv + g.etaPath * g.dl);
        float p = 0.0f;
        if (g.reflect) {
            if (g.compatReflect) {
                p += pr.specReflect * spec_.pdf(wo, g.h) * jac;
                if (pr.clearcoat > 0) p += pr.clearcoat * principled::gtr1D(g.h.z, coatAlpha_) * g.h.z * jac;
            }
            p += pr.diffuse * cosineHemispherePdf(wi.z);
        } else if (g.compatRefract) {
            p += pr.specTrans * spec_.pdf(wo, g.h) * jac;
        }
        return p;
    }

    uint32_t flags() const override {
        return kBSDFReflection | kBSDFGlossy | (brdf_ > 0 ? kBSDFDiffuse : 0u) | (bsdf_ > 0 ? kBSDFTransmission : 0u);
    }

private:
    struct Probabilities {
        float diffuse = 0, clearcoat = 0, specTrans = 0, specReflect = 0;
    };
    /// Mitsuba 3's lobe probabilities (principled.cpp, sample/pdf), normalised; F = F_dielectric(v·h).
    /// Front: main_specular_sampling_rate · (1 − bsdf (1 − F)) and · bsdf (1 − F), 0.25 clearcoat ·
    /// clearcoat_sampling_rate, brdf · diffuse_reflectance_sampling_rate. Inside: F and 1 − F only.
    Probabilities probabilities(bool front, float F) const {
        Probabilities p;
        if (front) {
            p.specReflect = c_.specRate * (1.0f - bsdf_ * (1.0f - F));
            p.specTrans = c_.specRate * bsdf_ * (1.0f - F);
            p.clearcoat = c_.hasClearcoat ? 0.25f * p_.clearcoat * c_.clearcoatRate : 0.0f;
            p.diffuse = brdf_ * c_.diffuseRate;
        } else {
            p.specReflect = F;
            p.specTrans = 1.0f - F;
        }
        const float sum = p.specReflect + p.specTrans + p.clearcoat + p.diffuse;
        if (!(sum > 0)) return Probabilities{0, 0, 0, 1};
        p.specReflect /= sum, p.specTrans /= sum, p.clearcoat /= sum, p.diffuse /= sum;
        return p;
    }

    struct Geometry {
        vec3 h;             // half vector (generalised for refraction), h.z > 0
        float dv, dl, F, etaPath;
        bool front, reflect, refract, compatReflect, compatRefract;
    };
    /// Mitsuba's half vector h ∝ v + l (reflection) or v + η' l (refraction, η' = η seen from v's
    /// side), turned to +z, its Fresnel F_dielectric(v·h, η) and the "mac_mic_compatibility" tests
    /// (both directions on the sides of the microfacet that their side of the surface allows).
    bool geometry(const vec3& wo, const vec3& wi, Geometry* g) const {
        if (wo.z == 0 || wi.z == 0) return false;
        g->front = wo.z > 0;
        g->reflect = wo.z * wi.z > 0;
        g->refract = !g->reflect;
        if (g->refract && !(bsdf_ > 0)) return false;
        g->etaPath = g->front ? c_.eta : 1.0f / c_.eta;
        vec3 h = wo + wi * (g->reflect ? 1.0f : g->etaPath);
        const float len = glm::length(h);
        if (!(len > 0)) return false;
        h /= len;
        if (h.z < 0) h = -h;
        g->h = h;
        g->dv = glm::dot(wo, h);
        g->dl = glm::dot(wi, h);
        const float s = g->front ? 1.0f : -1.0f;
        g->compatReflect = g->dv * s > 0 && g->dl * s > 0;
        g->compatRefract = g->dv * s > 0 && g->dl * s < 0;
        g->F = fresnelDielectric(g->dv, c_.eta);
        return true;
    }

    PrincipledM3Params p_;
    PrincipledM3Config c_;
    SampledSpectrum base_, ctint_, sqrtBase_, tintF0_;
    float brdf_ = 0, bsdf_ = 0, coatAlpha_ = 0.1f;
    MicrofacetDistribution spec_, coat_;
};

struct PrincipledThinParams {
    float roughness, anisotropic, specTrans, specTint, sheen, sheenTint, flatness, diffTrans, eta;
};

struct PrincipledThinConfig {
    float specReflectRate = 1.0f, specTransRate = 1.0f, diffReflectRate = 1.0f, diffTransRate = 1.0f;
};

class PrincipledThinBSDF final : public BSDF {
public:
    PrincipledThinBSDF(const SampledSpectrum& base, float lum, const PrincipledThinParams& p,
                       const PrincipledThinConfig& c)
        : p_(p), base_(base) {
        ctint_ = tintColour(base, lum);
        dt_ = p.diffTrans * 0.5f;  // Mitsuba: diff_trans ∈ [0, 2] is used halved
        const vec2 a = principled::anisotropicAlphas(p.roughness, p.anisotropic);
        refl_ = MicrofacetDistribution(MicrofacetType::GGX, a.x, a.y, true, ShadowingModel::SmithSeparable);
        const vec2 at =
            principled::anisotropicAlphas(principled::thinTransmissionRoughness(p.eta, p.roughness), p.anisotropic);
        trans_ = MicrofacetDistribution(MicrofacetType::GGX, at.x, at.y, true, ShadowingModel::SmithSeparable);
        // Mitsuba 3 principledthin.cpp: specular lobes ∝ spec_trans/2 each, cosine lobes
        // (1 − spec_trans)(1 − dt) and (1 − spec_trans) dt, times their sampling rates.
        pSR_ = p.specTrans * c.specReflectRate * 0.5f;
        pST_ = p.specTrans * c.specTransRate * 0.5f;
        pDR_ = c.diffReflectRate * (1.0f - p.specTrans) * (1.0f - dt_);
        pDT_ = c.diffTransRate * (1.0f - p.specTrans) * dt_;
        const float sum = pSR_ + pST_ + pDR_ + pDT_;
        if (sum > 0) pSR_ /= sum, pST_ /= sum, pDR_ /= sum, pDT_ /= sum;
        if (p.specTint > 0) tintF0_ = ctint_ * schlickF0FromEta(p.eta);
    }

    SampledSpectrum eval(const vec3& wo, const vec3& wi, TransportMode mode) const override {
        // Not reciprocal (F of the front side, l mirrored for the half vector): importance transport
        // takes the adjoint f*(wo, wi) = f(wi, wo) (Veach 1997 eq. 3.21).
        if (mode == TransportMode::Importance) return eval(wi, wo, TransportMode::Radiance);
        const int n = base_.size();
        SampledSpectrum f(n);
        if (wo.z == 0 || wi.z == 0) return f;
        // Symmetric: mirror both directions so that v is on the front.
        const float s = wo.z > 0 ? 1.0f : -1.0f;
        const vec3 v = wo * s, l = wi * s;
        const float cv = v.z, cl = std::abs(l.z);
        const bool reflect = l.z > 0;
        const vec3 h = glm::normalize(v + vec3(l.x, l.y, cl));  // l mirrored up for transmission
        const float dv = glm::dot(v, h), dl = glm::dot(l, h);
        const float st = p_.specTrans;
        if (st > 0 && dv > 0) {
            const float F = fresnelDielectric(dv, p_.eta);
            if (reflect && dl > 0) {
                SampledSpectrum Fthin(n, (1.0f - p_.specTint) * F);
                if (p_.specTint > 0) Fthin += schlickSpectrum(tintF0_, schlickWeightMitsuba(dv, p_.eta)) * p_.specTint;
                f += Fthin * (st * refl_.D(h) * refl_.G(l, v, h) / (4.0f * cv * cl));
            } else if (!reflect && dl < 0) {
                f += base_ * (st * (1.0f - F) * trans_.D(h) * trans_.G(l, v, h) / (4.0f * cv * cl));
            }
        }
        if (st < 1) {
            if (reflect && dt_ < 1) {
                const float w = (1.0f - st) * (1.0f - dt_);
                const float cosD = glm::dot(h, l);
                f += base_ * (w * diffuseLobe(cl, cv, cosD, p_.roughness, p_.flatness) * kInvPi);
                if (p_.sheen > 0) {
                    const float k = w * p_.sheen * schlickWeight(std::abs(cosD));
                    if (p_.sheenTint > 0)
                        f += lerp(p_.sheenTint, SampledSpectrum(n, 1.0f), ctint_) * k;
                    else
                        f += SampledSpectrum(n, k);
                }
            } else if (!reflect && dt_ > 0) {
                f += base_ * ((1.0f - st) * dt_ * kInvPi);
            }
        }
        return f;
    }

    std::optional<BSDFSample> sample(const vec3& wo, float uc, const vec2& u, TransportMode mode) const override {
        if (wo.z == 0) return std::nullopt;
        const float s = wo.z > 0 ? 1.0f : -1.0f;
        const vec3 v = wo * s;
        BSDFSample r;
        vec3 l;
        if (uc < pSR_) {
            const vec3 m = refl_.sampleNormal(v, u);
            l = reflect(v, m);
            if (!(l.z > 0 && glm::dot(v, m) > 0 && glm::dot(l, m) > 0)) return std::nullopt;
            r.flags = kBSDFReflection | kBSDFGlossy;
        } else if (uc < pSR_ + pST_) {
            // Reflect about the (rougher or smoother, [B15] Fig. 15) microfacet and pass to the
            // other side: a thin sheet does not bend the ray.
            const vec3 m = trans_.sampleNormal(v, u);
            l = reflect(v, m);
            l.z = -l.z;
            if (!(l.z < 0 && glm::dot(v, m) > 0 && glm::dot(l, m) < 0)) return std::nullopt;
            r.flags = kBSDFTransmission | kBSDFGlossy;
        } else if (uc < pSR_ + pST_ + pDR_) {
            l = sampleCosineHemisphere(u);
            r.flags = kBSDFReflection | kBSDFDiffuse;
        } else {
            l = -sampleCosineHemisphere(u);
            r.flags = kBSDFTransmission | kBSDFDiffuse;
        }
        r.wi = l * s;
        if (r.wi.z == 0) return std::nullopt;
        r.eta = 1.0f;
        r.pdf = pdf(wo, r.wi, mode);
        if (!(r.pdf > 0)) return std::nullopt;
        r.f = eval(wo, r.wi, mode);
        return r;
    }

    float pdf(const vec3& wo, const vec3& wi, TransportMode) const override {
        if (wo.z == 0 || wi.z == 0) return 0.0f;
        const float s = wo.z > 0 ? 1.0f : -1.0f;
        const vec3 v = wo * s, l = wi * s;
        const bool reflect = l.z > 0;
        float p = reflect ? pDR_ * cosineHemispherePdf(l.z) : pDT_ * cosineHemispherePdf(-l.z);
        if (pSR_ > 0 || pST_ > 0) {
            const vec3 lr(l.x, l.y, std::abs(l.z));
            const vec3 h = glm::normalize(v + lr);
            const float dv = glm::dot(v, h), dl = glm::dot(l, h);
            const float jac = 1.0f / (4.0f * std::abs(glm::dot(lr, h)));  // Walter et al. 2007 eq. 14
            if (dv > 0) {
                if (reflect && dl > 0) p += pSR_ * refl_.pdf(v, h) * jac;
                if (!reflect && dl < 0) p += pST_ * trans_.pdf(v, h) * jac;
            }
        }
        return p;
    }

    uint32_t flags() const override { return kBSDFReflection | kBSDFTransmission | kBSDFDiffuse | kBSDFGlossy; }

private:
    PrincipledThinParams p_;
    SampledSpectrum base_, ctint_, tintF0_;
    float dt_ = 0, pSR_ = 0, pST_ = 0, pDR_ = 1, pDT_ = 0;
    MicrofacetDistribution refl_, trans_;
};

/// Luminance of the base colour for Ctint: Mitsuba's Rec.709 Y of its RGB value. In spectral mode
/// the texture is evaluated once more at RGB-mode wavelengths, where reflectance spectra and
/// bitmaps return their RGB triple (as materials/principled.cpp does). Mitsuba 3 instead averages
/// ȳ(λ)·base(λ) over the path's sampled wavelengths (docs/materials_principled_cloth.md).
float baseLuminance(const SpectrumTexture& tex, const TextureQuery& q, const SampledWavelengths& wl,
                    const SampledSpectrum& base) {
    if (wl.isRGB()) return principled::luminanceMitsuba(vec3(base[0], base[1], base[2]));
    static const SampledWavelengths rgbWl = SampledWavelengths::rgb(defaultChannelWavelengths());
    const SampledSpectrum rgb = clampZero(tex.eval(q, rgbWl));
    return principled::luminanceMitsuba(vec3(rgb[0], rgb[1], rgb[2]));
}

float clampUnit(const FloatTexturePtr& t, const TextureQuery& q) { return std::clamp(t->eval(q), 0.0f, 1.0f); }

/// The parameters both plugins have.
struct CommonTextures {
    SpectrumTexturePtr baseColor;
    FloatTexturePtr roughness, anisotropic, specTrans, specTint, sheen, sheenTint, flatness;
};

/// Their values at a shading point (clamped to [0, 1]) and the base colour's luminance for Ctint
/// (only computed when a tint is on, as Mitsuba does).
struct CommonValues {
    SampledSpectrum base;
    float lum = 1.0f, roughness, anisotropic, specTrans, specTint, sheen, sheenTint, flatness;
};
CommonValues evalCommon(const CommonTextures& c, const TextureQuery& q, const SampledWavelengths& wl) {
    CommonValues v;
    v.base = clampZero(c.baseColor->eval(q, wl));
    v.roughness = clampUnit(c.roughness, q), v.anisotropic = clampUnit(c.anisotropic, q);
    v.specTrans = clampUnit(c.specTrans, q), v.specTint = clampUnit(c.specTint, q);
    v.sheen = clampUnit(c.sheen, q), v.sheenTint = clampUnit(c.sheenTint, q), v.flatness = clampUnit(c.flatness, q);
    if (v.specTint > 0 || (v.sheenTint > 0 && v.sheen > 0)) v.lum = baseLuminance(*c.baseColor, q, wl, v.base);
    return v;
}

class PrincipledM3Material final : public Material {
public:
    struct Textures {
        CommonTextures c;
        FloatTexturePtr metallic, clearcoat, clearcoatGloss;
    };
    PrincipledM3Material(Textures t, PrincipledM3Config c) : t_(std::move(t)), c_(c) {}

    const BSDF* getBSDF(const ShadingPoint& sp, SampledWavelengths& wl, Arena& arena) const override {
        const auto& q = sp.tex;
        const CommonValues v = evalCommon(t_.c, q, wl);
        const PrincipledM3Params p{v.roughness, v.anisotropic, clampUnit(t_.metallic, q), v.specTrans, v.specTint,
                                   v.sheen,     v.sheenTint,   v.flatness,                clampUnit(t_.clearcoat, q),
                                   clampUnit(t_.clearcoatGloss, q)};
        return arena.make<PrincipledM3BSDF>(v.base, v.lum, p, c_);
    }

private:
    Textures t_;
    PrincipledM3Config c_;
};

class PrincipledThinMaterial final : public Material {
public:
    struct Textures {
        CommonTextures c;
        FloatTexturePtr diffTrans, eta;
    };
    PrincipledThinMaterial(Textures t, PrincipledThinConfig c) : t_(std::move(t)), c_(c) {}

    const BSDF* getBSDF(const ShadingPoint& sp, SampledWavelengths& wl, Arena& arena) const override {
        const auto& q = sp.tex;
        const CommonValues v = evalCommon(t_.c, q, wl);
        const PrincipledThinParams p{v.roughness, v.anisotropic, v.specTrans, v.specTint, v.sheen, v.sheenTint, v.flatness,
                                     std::clamp(t_.diffTrans->eval(q), 0.0f, 2.0f), std::max(t_.eta->eval(q), 1e-3f)};
        return arena.make<PrincipledThinBSDF>(v.base, v.lum, p, c_);
    }

private:
    Textures t_;
    PrincipledThinConfig c_;
};

/// A float or texture parameter; a constant outside [lo, hi] is an error at its line (Mitsuba 3
/// documents the ranges but does not check them). Textured values are clamped when evaluated.
FloatTexturePtr rangedParam(const Properties& p, const std::string& name, float def, float lo = 0.0f, float hi = 1.0f) {
    FloatTexturePtr t = getFloatTexture(p, name, def);
    if (const auto* c = dynamic_cast<const ConstantFloatTexture*>(t.get()); c && !(c->value() >= lo && c->value() <= hi))
        failAt(p.locationOf(name), p.type(), ": parameter '", name, "' must be in [", lo, ", ", hi, "], got ", c->value());
    return t;
}

/// Mitsuba 3's get_flag (principledhelpers.h): a lobe is on when its parameter is given and is not
/// the float 0 (a texture always turns it on).
bool lobeFlag(const Properties& p, const std::string& name, const FloatTexturePtr& t) {
    if (!p.has(name)) return false;
    const auto* c = dynamic_cast<const ConstantFloatTexture*>(t.get());
    return !(c && c->value() == 0.0f);
}

float samplingRate(const Properties& p, const std::string& name, float def) {
    const float r = p.getFloat(name, def);
    if (!(r >= 0 && std::isfinite(r)))
        failAt(p.locationOf(name), p.type(), ": '", name, "' must be a finite sampling rate >= 0, got ", r);
    return r;
}

void rejectDisneyOnly(const Properties& p) {
    for (const char* name : {"subsurface", "specular_tint"})
        if (p.has(name))
            failAt(p.locationOf(name), p.type(), ": '", name, "' is a parameter of iris's Disney 2012 model (bsdf type ",
                   "'disney'), not of Mitsuba 3's principled", std::string(name) == "subsurface" ? " (its 'flatness' blends "
                   "in the same Hanrahan-Krueger term)" : " (use 'spec_tint')");
}

/// The parameters of both plugins (Mitsuba 3's names and defaults).
CommonTextures readCommon(const Properties& p) {
    rejectDisneyOnly(p);
    CommonTextures c;
    c.baseColor = getSpectrumTexture(p, "base_color", SpectrumKind::Reflectance, 0.5f);
    c.roughness = rangedParam(p, "roughness", 0.5f);
    c.anisotropic = rangedParam(p, "anisotropic", 0.0f);
    c.specTrans = rangedParam(p, "spec_trans", 0.0f);
    c.specTint = rangedParam(p, "spec_tint", 0.0f);
    c.sheen = rangedParam(p, "sheen", 0.0f);
    c.sheenTint = rangedParam(p, "sheen_tint", 0.0f);
    c.flatness = rangedParam(p, "flatness", 0.0f);
    return c;
}

std::shared_ptr<Material> createPrincipledMitsuba(const Properties& p) {
    PrincipledM3Material::Textures t;
    t.c = readCommon(p);
    t.metallic = rangedParam(p, "metallic", 0.0f);
    t.clearcoat = rangedParam(p, "clearcoat", 0.0f);
    t.clearcoatGloss = rangedParam(p, "clearcoat_gloss", 0.0f);
    PrincipledM3Config c;
    c.hasSpecTrans = lobeFlag(p, "spec_trans", t.c.specTrans);
    c.hasClearcoat = lobeFlag(p, "clearcoat", t.clearcoat);
    // Mitsuba 3 principled.cpp: `eta` and `specular` are alternatives (both given is an error);
    // eta = 1 and specular = 0 are moved to 1.001 and 1e-3 when the transmission lobe is on.
    if (p.has("eta")) {
        if (p.has("specular"))
            failAt(p.locationOf("specular"), p.type(), ": give either 'eta' or 'specular', not both (Mitsuba 3 derives one ",
                   "from the other)");
        c.eta = readConstantIOR(p, "eta", 1.5f);
        if (!(c.eta > 0 && std::isfinite(c.eta)))
            failAt(p.locationOf("eta"), p.type(), ": eta must be a finite relative index > 0, got ", c.eta);
        if (c.hasSpecTrans && c.eta == 1.0f) c.eta = 1.001f;
    } else {
        float specular = p.getFloat("specular", 0.5f);
        if (!(specular >= 0 && specular <= 1))
            failAt(p.locationOf("specular"), p.type(), ": parameter 'specular' must be in [0, 1], got ", specular);
        if (c.hasSpecTrans && specular == 0.0f) specular = 1e-3f;
        c.eta = principled::etaFromSpecular(specular);
    }
    c.specRate = samplingRate(p, "main_specular_sampling_rate", 1.0f);
    // Mitsuba 3's code default is 1 (its documentation says 0).
    c.clearcoatRate = samplingRate(p, "clearcoat_sampling_rate", 1.0f);
    c.diffuseRate = samplingRate(p, "diffuse_reflectance_sampling_rate", 1.0f);
    return std::make_shared<PrincipledM3Material>(std::move(t), c);
}


std::shared_ptr<Material> createPrincipledThin(const Properties& p) {
    PrincipledThinMaterial::Textures t;
    t.c = readCommon(p);
    t.diffTrans = rangedParam(p, "diff_trans", 0.0f, 0.0f, 2.0f);
    // Mitsuba 3 principledthin.cpp: eta is a float or texture, default 1.5 (no `specular`).
    t.eta = getFloatTexture(p, "eta", 1.5f);
    if (t.eta->isConstant() && !(t.eta->eval({}) > 0 && std::isfinite(t.eta->eval({}))))
        failAt(p.locationOf("eta"), p.type(), ": eta must be a finite relative index > 0, got ", t.eta->eval({}));
    if (p.has("specular"))
        failAt(p.locationOf("specular"), p.type(), ": has no 'specular' parameter (Mitsuba 3's principledthin takes 'eta')");
    PrincipledThinConfig c;
    c.specReflectRate = samplingRate(p, "specular_reflectance_sampling_rate", 1.0f);
    c.specTransRate = samplingRate(p, "specular_transmittance_sampling_rate", 1.0f);
    c.diffReflectRate = samplingRate(p, "diffuse_reflectance_sampling_rate", 1.0f);
    c.diffTransRate = samplingRate(p, "diffuse_transmittance_sampling_rate", 1.0f);
    return std::make_shared<PrincipledThinMaterial>(std::move(t), c);
}

}  // namespace

IRIS_REGISTER(MaterialRegistry, "principled", createPrincipledMitsuba);
IRIS_REGISTER(MaterialRegistry, "principledthin", createPrincipledThin);

}  // namespace iris
