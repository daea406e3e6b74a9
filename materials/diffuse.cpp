// Ideal diffuse (Lambertian) reflection: f = ρ/π, cosine-weighted sampling (pdf = cosθi/π).
// Mitsuba plugin "diffuse", parameter `reflectance` (spectrum or texture, default 0.5).
#include "core/registry.h"
#include "core/sampling.h"
#include "materials/material.h"
#include "materials/textures/texture_params.h"

namespace iris {
namespace {

class DiffuseBSDF final : public BSDF {
public:
    explicit DiffuseBSDF(const SampledSpectrum& r) : r_(r) {}

    SampledSpectrum eval(const vec3& wo, const vec3& wi, TransportMode) const override {
        if (wo.z <= 0 || wi.z <= 0) return SampledSpectrum(r_.size());
        return r_ * kInvPi;  // Lambert: f = ρ/π
    }
    std::optional<BSDFSample> sample(const vec3& wo, float, const vec2& u, TransportMode) const override {
        if (wo.z <= 0) return std::nullopt;
        BSDFSample s;
        s.wi = sampleCosineHemisphere(u);
        s.pdf = cosineHemispherePdf(s.wi.z);
        if (s.pdf <= 0) return std::nullopt;
        s.f = r_ * kInvPi;
        s.flags = kBSDFReflection | kBSDFDiffuse;
        return s;
    }
    float pdf(const vec3& wo, const vec3& wi, TransportMode) const override {
        if (wo.z <= 0 || wi.z <= 0) return 0.0f;
        return cosineHemispherePdf(wi.z);
    }
    uint32_t flags() const override { return kBSDFReflection | kBSDFDiffuse; }

private:
    SampledSpectrum r_;
};

class DiffuseMaterial final : public Material {
public:
    explicit DiffuseMaterial(SpectrumTexturePtr reflectance) : reflectance_(std::move(reflectance)) {}
    const BSDF* getBSDF(const ShadingPoint& sp, SampledWavelengths& wl, Arena& arena) const override {
        return arena.make<DiffuseBSDF>(clampZero(reflectance_->eval(sp.tex, wl)));
    }

private:
    SpectrumTexturePtr reflectance_;
};

std::shared_ptr<Material> createDiffuse(const Properties& p) {
    return std::make_shared<DiffuseMaterial>(getSpectrumTexture(p, "reflectance", SpectrumKind::Reflectance, 0.5f));
}

}  // namespace

IRIS_REGISTER(MaterialRegistry, "diffuse", createDiffuse);

}  // namespace iris
