// Normalised modified Phong BRDF (Lafortune & Willems 1994, "Using the Modified Phong Reflectance
// Model for Physically Based Rendering", eq. for the energy-normalised specular lobe):
//   f = ρd/π + ρs (n+2)/(2π) cosⁿα,   α = angle between wi and the mirror direction of wo.
// Sampling as Mitsuba 0.6 "phong" and thesis 000 §3.1.1 (eqs. 3.5–3.7): the specular lobe with
// probability ps = ρ̄s/(ρ̄s + ρ̄d) (ρ̄ = mean over wavelengths), cosα = ξ^{1/(n+1)}, φ = 2πξ' around
// the mirror direction with pdf (n+1)/(2π) cosⁿα; else cosine-weighted. Samples of the lobe that
// fall below the horizon are rejected (the pdf then integrates to less than 1 over the hemisphere).
// Parameters (Mitsuba 0.6): exponent (30), specular_reflectance (0.2), diffuse_reflectance (0.5).
#include "core/registry.h"
#include "core/sampling.h"
#include "materials/material.h"
#include "materials/textures/texture_params.h"

namespace iris {
namespace {

class PhongBSDF final : public BSDF {
public:
    PhongBSDF(const SampledSpectrum& kd, const SampledSpectrum& ks, float n) : kd_(kd), ks_(ks), n_(n) {
        const float d = kd_.average(), s = ks_.average();
        pSpec_ = d + s > 0 ? s / (d + s) : 0.0f;
    }

    SampledSpectrum eval(const vec3& wo, const vec3& wi, TransportMode) const override {
        if (wo.z <= 0 || wi.z <= 0) return SampledSpectrum(kd_.size());
        const float ca = glm::dot(wi, reflectLocal(wo));
        SampledSpectrum f = kd_ * kInvPi;
        if (ca > 0) f += ks_ * ((n_ + 2.0f) * kInv2Pi * std::pow(ca, n_));  // Lafortune & Willems 1994
        return f;
    }
    float pdf(const vec3& wo, const vec3& wi, TransportMode) const override {
        if (wo.z <= 0 || wi.z <= 0) return 0.0f;
        const float ca = glm::dot(wi, reflectLocal(wo));
        const float ps = ca > 0 ? (n_ + 1.0f) * kInv2Pi * std::pow(ca, n_) : 0.0f;  // thesis eq. 3.7
        return pSpec_ * ps + (1.0f - pSpec_) * cosineHemispherePdf(wi.z);
    }
    std::optional<BSDFSample> sample(const vec3& wo, float uc, const vec2& u, TransportMode mode) const override {
        if (wo.z <= 0) return std::nullopt;
        vec3 wi;
        if (uc < pSpec_) {
            // Thesis 000 eq. 3.5: cosα = ξ1^{1/(n+1)}, φ = 2πξ2, around the mirror direction.
            const float ca = std::pow(u.x, 1.0f / (n_ + 1.0f));
            const float sa = safeSqrt(1.0f - ca * ca);
            const float phi = 2.0f * kPi * u.y;
            const Frame fr = Frame::fromNormal(reflectLocal(wo));
            wi = fr.toWorld(vec3(sa * std::cos(phi), sa * std::sin(phi), ca));
            if (wi.z <= 0) return std::nullopt;
        } else {
            wi = sampleCosineHemisphere(u);
        }
        return sampleFromEval(wo, wi, kBSDFReflection | (uc < pSpec_ ? kBSDFGlossy : kBSDFDiffuse), mode);
    }
    uint32_t flags() const override { return kBSDFReflection | kBSDFDiffuse | kBSDFGlossy; }

private:
    SampledSpectrum kd_, ks_;
    float n_, pSpec_;
};

class PhongMaterial final : public Material {
public:
    PhongMaterial(SpectrumTexturePtr kd, SpectrumTexturePtr ks, FloatTexturePtr n)
        : kd_(std::move(kd)), ks_(std::move(ks)), n_(std::move(n)) {}
    const BSDF* getBSDF(const ShadingPoint& sp, SampledWavelengths& wl, Arena& arena) const override {
        return arena.make<PhongBSDF>(clampZero(kd_->eval(sp.tex, wl)), clampZero(ks_->eval(sp.tex, wl)),
                                     std::max(0.0f, n_->eval(sp.tex)));
    }

private:
    SpectrumTexturePtr kd_, ks_;
    FloatTexturePtr n_;
};

std::shared_ptr<Material> createPhong(const Properties& p) {
    FloatTexturePtr exponent = getFloatTexture(p, "exponent", 30.0f);
    if (exponent->isConstant() && !(exponent->eval({}) >= 0))
        failAt(p.locationOf("exponent"), "phong: exponent must be >= 0, got ", exponent->eval({}));
    return std::make_shared<PhongMaterial>(getSpectrumTexture(p, "diffuse_reflectance", SpectrumKind::Reflectance, 0.5f),
                                           getSpectrumTexture(p, "specular_reflectance", SpectrumKind::Reflectance, 0.2f),
                                           std::move(exponent));
}

}  // namespace

IRIS_REGISTER(MaterialRegistry, "phong", createPhong);

}  // namespace iris
