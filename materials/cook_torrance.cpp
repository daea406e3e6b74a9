// Cook-Torrance BRDF as in thesis 003 §4.12 (Cook & Torrance 1982):
//   f = kd · albedo/π + (1 − kd) · D(h) F(l,h) G(l,v,h) / (4 (n·l)(n·v))
// with the Beckmann D (roughness r = α), Schlick's Fresnel F = F0 + (1 − F0)(1 − l·h)⁵
// (Schlick 1994) and the V-cavity G = min(1, 2(n·h)(n·v)/(v·h), 2(n·h)(n·l)/(v·h)).
// Sampling: cosine-weighted for the diffuse term, Beckmann visible normals (or D cosθm) for the
// specular term, chosen with probability ∝ kd·mean(albedo) and (1 − kd) respectively.
// Parameters (iris plugin "cook_torrance", names after the thesis):
//   albedo     diffuse colour (spectrum/texture, default 0.5)
//   kd         diffuse weight in [0, 1] (float, default 0.5)
//   roughness  Beckmann α (float/texture, default 0.3)
//   f0         Fresnel reflectance at normal incidence (spectrum/texture, default 0.04)
//   sample_visible  visible-normal sampling (default true)
#include "core/registry.h"
#include "core/sampling.h"
#include "materials/fresnel.h"
#include "materials/material.h"
#include "materials/microfacet.h"
#include "materials/textures/texture_params.h"

namespace iris {
namespace {

class CookTorranceBSDF final : public BSDF {
public:
    CookTorranceBSDF(const MicrofacetDistribution& d, const SampledSpectrum& albedo, const SampledSpectrum& f0, float kd)
        : d_(d), albedo_(albedo), f0_(f0), kd_(kd) {
        const float wd = kd_ * albedo_.average(), ws = 1.0f - kd_;
        pSpec_ = wd + ws > 0 ? ws / (wd + ws) : 0.5f;
    }

    SampledSpectrum eval(const vec3& wo, const vec3& wi, TransportMode) const override {
        const int n = albedo_.size();
        if (wo.z <= 0 || wi.z <= 0) return SampledSpectrum(n);
        SampledSpectrum f = albedo_ * (kd_ * kInvPi);
        const vec3 h = glm::normalize(wo + wi);
        const float D = d_.D(h);
        if (D > 0 && kd_ < 1.0f) {
            const float G = d_.G(wi, wo, h);
            f += fresnelSchlick(glm::dot(wi, h), f0_) * ((1.0f - kd_) * D * G / (4.0f * wi.z * wo.z));
        }
        return f;
    }
    float pdf(const vec3& wo, const vec3& wi, TransportMode) const override {
        if (wo.z <= 0 || wi.z <= 0) return 0.0f;
        const vec3 h = glm::normalize(wo + wi);
        const float ps = d_.pdf(wo, h) / (4.0f * std::abs(glm::dot(wo, h)));
        return pSpec_ * ps + (1.0f - pSpec_) * cosineHemispherePdf(wi.z);
    }
    std::optional<BSDFSample> sample(const vec3& wo, float uc, const vec2& u, TransportMode mode) const override {
        if (wo.z <= 0) return std::nullopt;
        vec3 wi;
        const bool spec = uc < pSpec_;
        if (spec) {
            wi = reflect(wo, d_.sampleNormal(wo, u));
            if (wi.z <= 0) return std::nullopt;
        } else {
            wi = sampleCosineHemisphere(u);
        }
        return sampleFromEval(wo, wi, kBSDFReflection | (spec ? kBSDFGlossy : kBSDFDiffuse), mode);
    }
    uint32_t flags() const override { return kBSDFReflection | kBSDFDiffuse | kBSDFGlossy; }

private:
    MicrofacetDistribution d_;
    SampledSpectrum albedo_, f0_;
    float kd_, pSpec_;
};

class CookTorranceMaterial final : public Material {
public:
    CookTorranceMaterial(SpectrumTexturePtr albedo, SpectrumTexturePtr f0, FloatTexturePtr r, float kd, bool visible)
        : albedo_(std::move(albedo)), f0_(std::move(f0)), r_(std::move(r)), kd_(kd), visible_(visible) {}
    const BSDF* getBSDF(const ShadingPoint& sp, SampledWavelengths& wl, Arena& arena) const override {
        const float r = r_->eval(sp.tex);
        const MicrofacetDistribution d(MicrofacetType::Beckmann, r, r, visible_, ShadowingModel::VCavity);
        return arena.make<CookTorranceBSDF>(d, clampZero(albedo_->eval(sp.tex, wl)), clampZero(f0_->eval(sp.tex, wl)), kd_);
    }

private:
    SpectrumTexturePtr albedo_, f0_;
    FloatTexturePtr r_;
    float kd_;
    bool visible_;
};

std::shared_ptr<Material> createCookTorrance(const Properties& p) {
    const float kd = p.getFloat("kd", 0.5f);
    if (!(kd >= 0 && kd <= 1)) failAt(p.locationOf("kd"), "cook_torrance: kd must be in [0, 1], got ", kd);
    FloatTexturePtr roughness = getFloatTexture(p, "roughness", 0.3f);
    if (roughness->isConstant() && !(roughness->eval({}) >= 0))
        failAt(p.locationOf("roughness"), "cook_torrance: roughness must be >= 0, got ", roughness->eval({}));
    return std::make_shared<CookTorranceMaterial>(getSpectrumTexture(p, "albedo", SpectrumKind::Reflectance, 0.5f),
                                                  getSpectrumTexture(p, "f0", SpectrumKind::Reflectance, 0.04f),
                                                  std::move(roughness), kd,
                                                  p.getBool("sample_visible", true));
}

}  // namespace

IRIS_REGISTER(MaterialRegistry, "cook_torrance", createCookTorrance);

}  // namespace iris
