// Smooth plastic (Mitsuba "plastic"): a smooth dielectric coat over a Lambertian base. The α → 0
// limit of roughplastic (thesis 000 §2.5 with a smooth interface); needs no tables.
//   specular: delta reflection with exact Fresnel F(μo, η), coefficient ks
//   diffuse:  ρ' (1 − F(μi)) (1 − F(μo)) / (π η²),  ρ' = ρ/(1 − Fdr) or ρ/(1 − ρ Fdr) (nonlinear)
//   Fdr = 1 − (1/η²) 2∫₀¹ (1 − F(μ, η)) μ dμ (internal diffuse reflectance, by reciprocity).
//
// Parameters: int_ior (1.49), ext_ior (1.000277) (floats or preset names), diffuse_reflectance (0.5),
// specular_reflectance (1.0), nonlinear (false).
#include "core/registry.h"
#include "materials/fresnel_mueller.h"
#include "materials/material.h"
#include "materials/textures/texture_params.h"
#include "materials/thesis_rough_coat.h"
#include "spectral/ior_params.h"

namespace iris {
namespace {

class PlasticBSDF final : public BSDF {
public:
    PlasticBSDF(float eta, float fdr, const SampledSpectrum& ks, const SampledSpectrum& rho, bool nonlinear)
        : eta_(eta), ks_(ks), rhoEff_(rho), rhoAvg_(rho.average()) {
        for (int c = 0; c < rho.size(); ++c) rhoEff_[c] = roughCoatAlbedo(rho[c], fdr, nonlinear);
    }

    SampledSpectrum eval(const vec3& wo, const vec3& wi, TransportMode) const override {
        SampledSpectrum f(ks_.size());
        if (wo.z <= 0 || wi.z <= 0) return f;
        const float d = (1.0f - fresnelDielectric(wi.z, eta_)) * (1.0f - fresnelDielectric(wo.z, eta_)) * kInvPi /
                        (eta_ * eta_);
        for (int c = 0; c < f.size(); ++c) f[c] = rhoEff_[c] * d;
        return f;
    }

    float specularProbability(const vec3& wo) const {
        return roughCoatSpecularProbability(ks_.average(), rhoAvg_, 1.0f - fresnelDielectric(wo.z, eta_));
    }

    std::optional<BSDFSample> sample(const vec3& wo, float uc, const vec2& u, TransportMode mode) const override {
        if (wo.z <= 0) return std::nullopt;
        const float ps = specularProbability(wo);
        BSDFSample s;
        if (uc < ps) {
            // Delta lobe: f = ks F / |cosθi|, pdf = discrete probability (materials/bsdf.h).
            s.wi = reflectLocal(wo);
            s.pdf = ps;
            s.f = ks_ * (fresnelDielectric(wo.z, eta_) / wo.z);
            s.flags = kBSDFReflection | kBSDFSpecular;
            return s;
        }
        s.wi = sampleCosineHemisphere(u);
        if (s.wi.z <= 0) return std::nullopt;
        s.pdf = (1.0f - ps) * cosineHemispherePdf(s.wi.z);
        if (!(s.pdf > 0)) return std::nullopt;
        s.f = eval(wo, s.wi, mode);
        s.flags = kBSDFReflection | kBSDFDiffuse;
        return s;
    }

    float pdf(const vec3& wo, const vec3& wi, TransportMode) const override {
        if (wo.z <= 0 || wi.z <= 0) return 0.0f;
        return (1.0f - specularProbability(wo)) * cosineHemispherePdf(wi.z);
    }

    uint32_t flags() const override { return kBSDFReflection | kBSDFSpecular | kBSDFDiffuse; }
    /// Polarized: the specular lobe is the coat's Fresnel reflection matrix, the diffuse lobe a
    /// depolarizer (Mitsuba 3's plastic depolarizes both; its pplastic polarizes the specular lobe
    /// as here; docs/polarization.md).
    std::optional<PolarizedBSDFSample> sampleMueller(const vec3& wo, float uc, const vec2& u, TransportMode mode) const override {
        const std::optional<BSDFSample> s = sample(wo, uc, u, mode);
        if (!s || !s->isSpecular()) return withEvalMueller(*this, s, wo, mode);
        const SampledSpectrum eta(ks_.size(), eta_);
        return withMueller(s, fresnelReflectionMueller(vec3(0, 0, 1), s->wi, wo, eta), ks_ / wo.z);
    }

private:
    float eta_;
    SampledSpectrum ks_, rhoEff_;
    float rhoAvg_;
};

class PlasticMaterial final : public Material {
public:
    explicit PlasticMaterial(const Properties& p) {
        // Mitsuba 3's defaults "polypropylene" and "air"; a float or a preset name (spectral/ior_params.h).
        const float intIor = readConstantIOR(p, "int_ior", 1.49f), extIor = readConstantIOR(p, "ext_ior", 1.000277f);
        eta_ = intIor / extIor;
        // Fdr = 1 − Td with Td = (1/η²) 2∫(1 − F)μ dμ (α = 0 path of the integrator: no tables).
        fdr_ = float(1.0 - roughInternalDiffuseIntegral(MicrofacetType::Beckmann, eta_, 0.0, 1, 128));
        rho_ = getSpectrumTexture(p, "diffuse_reflectance", SpectrumKind::Reflectance, 0.5f);
        ks_ = getSpectrumTexture(p, "specular_reflectance", SpectrumKind::Reflectance, 1.0f);
        nonlinear_ = p.getBool("nonlinear", false);
    }

    const BSDF* getBSDF(const ShadingPoint& sp, SampledWavelengths& wl, Arena& arena) const override {
        return arena.make<PlasticBSDF>(eta_, fdr_, clampZero(ks_->eval(sp.tex, wl)), clampZero(rho_->eval(sp.tex, wl)),
                                       nonlinear_);
    }

private:
    float eta_, fdr_;
    SpectrumTexturePtr rho_, ks_;
    bool nonlinear_;
};

std::shared_ptr<Material> createPlastic(const Properties& p) { return std::make_shared<PlasticMaterial>(p); }

}  // namespace

IRIS_REGISTER(MaterialRegistry, "plastic", createPlastic);

}  // namespace iris
