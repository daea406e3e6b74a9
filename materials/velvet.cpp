// Velvet BRDF of Ashikhmin (Ashikhmin, Premože & Shirley 2000, "A Microfacet-based BRDF
// Generator", velvet distribution; Ashikhmin 2007, "Distribution-based BRDFs", with the smooth
// denominator that replaces the shadowing term), described in thesis 004 §5.2.2 (eq. 5.2):
//
//   f = R · D_velvet(σ, θh) / (4 (cosθi + cosθo − cosθi cosθo))
//   D_velvet = (1 + 4 exp(−cot²θh/σ²) / sin⁴θh) / (π (1 + 4σ²))   (∫ D cosθh dω = 1)
//
// R (`reflectance`, default 0.5) is a constant colour in place of the Fresnel factor (the models
// above use no Fresnel for the fibre sheen either). `sigma` σ (default 0.5, > 0) is the width of
// the grazing peak. Reciprocal (symmetric in wo, wi). Sampling: p ∝ cos^(1/2)θ (cloth_distributions.h).
#include "core/registry.h"
#include "materials/cloth_distributions.h"
#include "materials/cloth_sampling.h"
#include "materials/material.h"
#include "materials/textures/texture_params.h"

namespace iris {
namespace {

class VelvetBSDF final : public cloth::SqrtCosineSampledBSDF {
public:
    VelvetBSDF(const SampledSpectrum& r, float sigma) : r_(r), sigma_(sigma) {}

    SampledSpectrum eval(const vec3& wo, const vec3& wi, TransportMode) const override {
        if (wo.z <= 0 || wi.z < cloth::kMinCosTheta) return SampledSpectrum(r_.size());
        const vec3 h = glm::normalize(wo + wi);
        return r_ * (cloth::velvetD(sigma_, h.z) * cloth::neubeltV(wo.z, wi.z));
    }
    uint32_t flags() const override { return kBSDFReflection | kBSDFGlossy; }

private:
    SampledSpectrum r_;
    float sigma_;
};

class VelvetMaterial final : public Material {
public:
    VelvetMaterial(SpectrumTexturePtr r, FloatTexturePtr sigma) : r_(std::move(r)), sigma_(std::move(sigma)) {}
    const BSDF* getBSDF(const ShadingPoint& sp, SampledWavelengths& wl, Arena& arena) const override {
        return arena.make<VelvetBSDF>(clampZero(r_->eval(sp.tex, wl)), std::max(sigma_->eval(sp.tex), 1e-3f));
    }

private:
    SpectrumTexturePtr r_;
    FloatTexturePtr sigma_;
};

std::shared_ptr<Material> createVelvet(const Properties& p) {
    auto r = getSpectrumTexture(p, "reflectance", SpectrumKind::Reflectance, 0.5f);
    auto sigma = getFloatTexture(p, "sigma", 0.5f);
    if (const auto* c = dynamic_cast<const ConstantFloatTexture*>(sigma.get()); c && !(c->value() > 0))
        failAt(p.locationOf("sigma"), "velvet: sigma must be > 0, got ", c->value());
    return std::make_shared<VelvetMaterial>(std::move(r), std::move(sigma));
}

}  // namespace

IRIS_REGISTER(MaterialRegistry, "velvet", createVelvet);

}  // namespace iris
