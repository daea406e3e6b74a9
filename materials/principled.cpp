// Disney "principled" BRDF (Burley 2012, "Physically-Based Shading at Disney", SIGGRAPH 2012
// course notes §5 + Appendix B, and the reference `disney.brdf` of the Disney BRDF Explorer),
// reflection only, one-sided. Scalar terms: materials/principled_terms.h; GGX: microfacet.h.
//
//   f = (1 − metallic) · [ Cd/π · mix(F_d, ss, subsurface) + F_sheen ]
//     + D_s G_s F_s / (4 cosθl cosθv)                                   (anisotropic GGX lobe)
//     + 0.25 clearcoat · D_r G_r F_r / (4 cosθl cosθv)                   (GTR1 clear coat)
//   Ctint  = Cd / lum(Cd) (1 if lum = 0)
//   Cspec0 = mix(specular · 0.08 · mix(1, Ctint, specularTint), Cd, metallic)
//   F_s    = mix(Cspec0, 1, F_H), F_H = (1 − cosθd)^5                  (Schlick)
//   F_sheen = F_H · sheen · mix(1, Ctint, sheenTint)
//   D_s    = GGX(αx, αy), αx = r²/aspect, αy = r²·aspect, aspect = sqrt(1 − 0.9 anisotropic)
//   G_s    = Smith GGX G1(l) G1(v) with the same αx, αy (Burley 2015 notes / disney.brdf: the
//            2012 remapping αg = (0.5 + r/2)² of G was dropped)
//   D_r    = GTR1(mix(0.1, 0.001, clearcoatGloss)),  F_r = mix(0.04, 1, F_H),
//   G_r    = Smith GGX G1(l) G1(v) with α = 0.25.
//
// Luminance in spectral mode: lum(Cd) is the Rec.709 Y of the base colour's *RGB* value, found
// by evaluating the base-colour texture at RGB-mode wavelengths (a reflectance spectrum returns
// its RGB triple there, see spectral/spectrum.h). So Ctint is the same spectral function in both
// modes (Cd(λ)/Y_rgb), and in RGB mode it is exactly Cd/lum(Cd).
//
// Sampling (one-sample MIS over three strategies, pdf = Σ p_i pdf_i): cosine hemisphere for the
// diffuse/subsurface/sheen part, visible-normal GGX for the specular lobe, D_GTR1 cosθh normal
// sampling for the clear coat; p_i ∝ (1 − metallic)·lum-average(Cd) + sheen term, average of
// F_s(cosθv), 0.25 clearcoat F_r(cosθv).
//
// Mitsuba 3 parameter names: base_color, roughness, anisotropic, metallic, specular, spec_tint,
// sheen, sheen_tint, clearcoat, clearcoat_gloss (Mitsuba defaults); `eta` instead of `specular`
// (a float or an IOR preset name, spectral/ior_params.h), read as Mitsuba 3 relates the two,
// 0.08 specular = ((η − 1)/(η + 1))²; `subsurface` (Burley's name, not in Mitsuba 3's principled)
// and `specular_tint` (Burley's name, alias of spec_tint).
#include "core/registry.h"
#include "core/sampling.h"
#include "materials/material.h"
#include "materials/microfacet.h"
#include "materials/principled.h"
#include "materials/principled_terms.h"
#include "materials/fresnel.h"
#include "materials/textures/texture_params.h"
#include "spectral/ior_params.h"

namespace iris {
namespace {

struct PrincipledParams {
    float subsurface, metallic, specular, specularTint, roughness, anisotropic, sheen, sheenTint, clearcoat,
        clearcoatGloss;
};

class PrincipledBSDF final : public BSDF {
public:
    PrincipledBSDF(const SampledSpectrum& baseColor, float baseLuminance, const PrincipledParams& p) : p_(p) {
        const int n = baseColor.size();
        cd_ = baseColor;
        const SampledSpectrum ctint = baseLuminance > 0 ? baseColor / baseLuminance : SampledSpectrum(n, 1.0f);
        const SampledSpectrum one(n, 1.0f);
        // Cspec0 = mix(specular·0.08·mix(1, Ctint, specularTint), Cd, metallic)
        cspec0_ = lerp(p.metallic, (p.specular * 0.08f) * lerp(p.specularTint, one, ctint), baseColor);
        // Csheen = sheen · mix(1, Ctint, sheenTint)   (the F_H factor is applied in eval)
        csheen_ = p.sheen * lerp(p.sheenTint, one, ctint);
        const vec2 a = principled::anisotropicAlphas(p.roughness, p.anisotropic);
        spec_ = MicrofacetDistribution(MicrofacetType::GGX, a.x, a.y, true, ShadowingModel::SmithSeparable);
        coat_ = MicrofacetDistribution(MicrofacetType::GGX, 0.25f, 0.25f, false, ShadowingModel::SmithSeparable);
        coatAlpha_ = principled::clearcoatAlpha(p.clearcoatGloss);
        diffuseWeight_ = (1.0f - p.metallic) * (baseColor.average() + csheen_.average() * 0.1f);
    }

    SampledSpectrum eval(const vec3& wo, const vec3& wi, TransportMode) const override {
        const int n = cd_.size();
        if (wo.z <= 0 || wi.z <= 0) return SampledSpectrum(n);
        vec3 h = wo + wi;
        const float hl = glm::length(h);
        if (!(hl > 0)) return SampledSpectrum(n);
        h /= hl;
        const float cosL = wi.z, cosV = wo.z, cosD = glm::dot(wi, h);
        const float fh = principled::schlickWeight(cosD);
        SampledSpectrum f(n);
        if (p_.metallic < 1.0f) {
            // Diffuse / subsurface (Burley 2012 §5.3) and sheen, both × (1 − metallic).
            const float fd = principled::burleyDiffuseFactor(cosL, cosV, cosD, p_.roughness);
            const float ss = p_.subsurface > 0 ? principled::subsurfaceFactor(cosL, cosV, cosD, p_.roughness) : 0.0f;
            const float diffuse = lerp(p_.subsurface, fd, ss) * kInvPi;
            f += (cd_ * diffuse + csheen_ * fh) * (1.0f - p_.metallic);
        }
        // Specular: D G F / (4 cosθl cosθv), F = mix(Cspec0, 1, F_H).
        const float dg = spec_.D(h) * spec_.G(wi, wo, h) / (4.0f * cosL * cosV);
        f += (cspec0_ + (1.0f - cspec0_) * fh) * dg;
        if (p_.clearcoat > 0) {
            const float fr = lerp(fh, 0.04f, 1.0f);
            const float gr = coat_.G(wi, wo, h);
            f += SampledSpectrum(n, 0.25f * p_.clearcoat * principled::gtr1D(h.z, coatAlpha_) * fr * gr /
                                        (4.0f * cosL * cosV));
        }
        return f;
    }

    std::optional<BSDFSample> sample(const vec3& wo, float uc, const vec2& u, TransportMode mode) const override {
        if (wo.z <= 0) return std::nullopt;
        float pd, ps, pc;
        lobeProbabilities(wo, pd, ps, pc);
        BSDFSample s;
        if (uc < pd) {
            s.wi = sampleCosineHemisphere(u);
            s.flags = kBSDFReflection | kBSDFDiffuse;
        } else if (uc < pd + ps) {
            const vec3 m = spec_.sampleNormal(wo, u);
            s.wi = reflect(wo, m);
            s.flags = kBSDFReflection | kBSDFGlossy;
        } else {
            const vec3 m = principled::sampleGTR1(u, coatAlpha_);
            s.wi = reflect(wo, m);
            s.flags = kBSDFReflection | kBSDFGlossy;
        }
        if (s.wi.z <= 0) return std::nullopt;
        s.pdf = mixturePdf(wo, s.wi, pd, ps, pc);
        if (!(s.pdf > 0)) return std::nullopt;
        s.f = eval(wo, s.wi, mode);
        return s;
    }

    float pdf(const vec3& wo, const vec3& wi, TransportMode) const override {
        if (wo.z <= 0 || wi.z <= 0) return 0.0f;
        float pd, ps, pc;
        lobeProbabilities(wo, pd, ps, pc);
        return mixturePdf(wo, wi, pd, ps, pc);
    }

    uint32_t flags() const override {
        return kBSDFReflection | kBSDFGlossy | (p_.metallic < 1.0f ? kBSDFDiffuse : 0u);
    }

private:
    /// Lobe-selection probabilities from approximate lobe albedos at wo.
    void lobeProbabilities(const vec3& wo, float& pd, float& ps, float& pc) const {
        const float fv = principled::schlickWeight(wo.z);
        const float wd = diffuseWeight_;
        const float ws = (cspec0_ + (1.0f - cspec0_) * fv).average();
        const float wc = 0.25f * p_.clearcoat * lerp(fv, 0.04f, 1.0f);
        const float sum = wd + ws + wc;
        if (!(sum > 0)) {  // black material: sample the specular lobe (any valid pdf will do)
            pd = 0, ps = 1, pc = 0;
            return;
        }
        pd = wd / sum, ps = ws / sum, pc = wc / sum;
    }

    float mixturePdf(const vec3& wo, const vec3& wi, float pd, float ps, float pc) const {
        const vec3 h = glm::normalize(wo + wi);
        const float woh = glm::dot(wo, h);
        if (!(woh > 0)) return pd * cosineHemispherePdf(wi.z);
        float p = pd * cosineHemispherePdf(wi.z);
        // Reflection Jacobian dωh/dωi = 1/(4 wo·h) (Walter et al. 2007 eq. 14).
        if (ps > 0) p += ps * spec_.pdf(wo, h) / (4.0f * woh);
        if (pc > 0) p += pc * principled::gtr1D(h.z, coatAlpha_) * h.z / (4.0f * woh);
        return p;
    }

    PrincipledParams p_;
    SampledSpectrum cd_, cspec0_, csheen_;
    MicrofacetDistribution spec_, coat_;
    float coatAlpha_ = 0.1f, diffuseWeight_ = 0;
};

class PrincipledMaterial final : public Material {
public:
    struct Textures {
        SpectrumTexturePtr baseColor;
        FloatTexturePtr subsurface, metallic, specular, specularTint, roughness, anisotropic, sheen, sheenTint,
            clearcoat, clearcoatGloss;
    };
    explicit PrincipledMaterial(Textures t) : t_(std::move(t)) {}

    const BSDF* getBSDF(const ShadingPoint& sp, SampledWavelengths& wl, Arena& arena) const override {
        const auto& q = sp.tex;
        auto unit = [&](const FloatTexturePtr& tex) { return std::clamp(tex->eval(q), 0.0f, 1.0f); };
        const PrincipledParams p{unit(t_.subsurface), unit(t_.metallic),    unit(t_.specular),
                                 unit(t_.specularTint), unit(t_.roughness), unit(t_.anisotropic),
                                 unit(t_.sheen),        unit(t_.sheenTint), unit(t_.clearcoat),
                                 unit(t_.clearcoatGloss)};
        const SampledSpectrum base = clampZero(t_.baseColor->eval(q, wl));
        return arena.make<PrincipledBSDF>(base, baseLuminance(q, wl, base), p);
    }

private:
    /// Rec.709 luminance of the base colour's RGB value (see the file comment).
    float baseLuminance(const TextureQuery& q, const SampledWavelengths& wl, const SampledSpectrum& base) const {
        if (wl.isRGB()) return principled::luminance(vec3(base[0], base[1], base[2]));
        static const SampledWavelengths rgbWl = SampledWavelengths::rgb(defaultChannelWavelengths());
        const SampledSpectrum rgb = clampZero(t_.baseColor->eval(q, rgbWl));
        return principled::luminance(vec3(rgb[0], rgb[1], rgb[2]));
    }

    Textures t_;
};

/// `specular` from Mitsuba 3's `eta`: the same normal-incidence reflectance, 0.08 specular =
/// ((η − 1)/(η + 1))² (Mitsuba 3, src/bsdfs/principled.cpp: eta and specular are in one-to-one
/// correspondence and exclude each other).
FloatTexturePtr specularFromEta(const Properties& p) {
    if (p.has("specular")) failAt(p.locationOf("eta"), p.type(), ": give either 'eta' or 'specular', not both");
    const float eta = readConstantIOR(p, "eta", 1.5f);
    const float specular = schlickF0FromEta(eta) / 0.08f;
    if (!(specular <= 1.0f))
        failAt(p.locationOf("eta"), p.type(), ": eta = ", eta, " needs specular = ", specular, " > 1, beyond this model's ",
               "range (0.08 specular is its largest normal-incidence reflectance; eta in [0.559, 1.788])");
    return std::make_shared<ConstantFloatTexture>(specular);
}

}  // namespace

std::shared_ptr<Material> createDisneyPrincipled(const Properties& p) {
    auto unitParam = [&](const std::string& name, float def) {
        FloatTexturePtr t = getFloatTexture(p, name, def);
        if (const auto* c = dynamic_cast<const ConstantFloatTexture*>(t.get()); c && !(c->value() >= 0 && c->value() <= 1))
            failAt(p.locationOf(name), p.type(), ": parameter '", name, "' must be in [0, 1], got ", c->value());
        return t;
    };
    PrincipledMaterial::Textures t;
    t.baseColor = getSpectrumTexture(p, "base_color", SpectrumKind::Reflectance, 0.5f);
    t.subsurface = unitParam("subsurface", 0.0f);
    t.metallic = unitParam("metallic", 0.0f);
    t.specular = p.has("eta") ? specularFromEta(p) : unitParam("specular", 0.5f);
    if (p.has("spec_tint") && p.has("specular_tint"))
        failAt(p.locationOf("specular_tint"), p.type(), ": give either 'spec_tint' or its alias 'specular_tint', not both");
    t.specularTint = unitParam(p.has("specular_tint") ? "specular_tint" : "spec_tint", 0.0f);
    t.roughness = unitParam("roughness", 0.5f);
    t.anisotropic = unitParam("anisotropic", 0.0f);
    t.sheen = unitParam("sheen", 0.0f);
    t.sheenTint = unitParam("sheen_tint", 0.0f);
    t.clearcoat = unitParam("clearcoat", 0.0f);
    t.clearcoatGloss = unitParam("clearcoat_gloss", 0.0f);
    return std::make_shared<PrincipledMaterial>(std::move(t));
}

// `disney` in every scene version; `principled` chooses between this model (version 0.x) and
// Mitsuba 3's (materials/principled_mitsuba.cpp).
IRIS_REGISTER(MaterialRegistry, "disney", createDisneyPrincipled);

}  // namespace iris
