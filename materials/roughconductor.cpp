// Rough conductor: microfacet reflection f = F(wi·m) D(m) G(wi, wo, m) / (4 cosθi cosθo)
// (thesis 000 eq. 2.6; Cook & Torrance 1982; Walter et al. 2007 eq. 20) with the exact conductor
// Fresnel term, sampled by visible normals (or D(m) cosθm). Mitsuba 3 plugin "roughconductor":
//   material / eta / k / specular_reflectance / ext_ior   as "conductor"
//   distribution ("beckmann"), alpha (0.1), alpha_u / alpha_v, sample_visible (true),
//   masking, beckmann_rational_g1   see MicrofacetParams (materials/microfacet.h)
#include "core/registry.h"
#include "spectral/conductor_presets.h"
#include "materials/fresnel.h"
#include "materials/fresnel_mueller.h"
#include "materials/material.h"
#include "materials/microfacet.h"
#include "materials/textures/texture_params.h"

namespace iris {
namespace {

class RoughConductorBSDF final : public BSDF {
public:
    RoughConductorBSDF(const MicrofacetDistribution& d, const SampledSpectrum& eta, const SampledSpectrum& k,
                       const SampledSpectrum& scale, bool mirror)
        : d_(d), eta_(eta), k_(k), scale_(scale), mirror_(mirror) {}

    SampledSpectrum eval(const vec3& wo, const vec3& wi, TransportMode) const override {
        vec3 m;
        const float t = microfacetTerm(wo, wi, &m);
        if (t == 0) return SampledSpectrum(scale_.size());
        return fresnel(glm::dot(wi, m)) * scale_ * t;
    }
    /// Mitsuba 3 roughconductor.cpp, polarized: the Fresnel matrix of the microfacet m.
    MuellerSpectrum evalMueller(const vec3& wo, const vec3& wi, TransportMode) const override {
        vec3 m;
        const float t = microfacetTerm(wo, wi, &m);
        if (t == 0) return MuellerSpectrum::depolarizer(SampledSpectrum(scale_.size()));
        const int n = scale_.size();
        const SampledSpectrum eta = mirror_ ? SampledSpectrum(n) : eta_, k = mirror_ ? SampledSpectrum(n, 1.0f) : k_;
        return fresnelReflectionMueller(m, wi, wo, eta, &k) * (scale_ * t);
    }
    std::optional<PolarizedBSDFSample> sampleMueller(const vec3& wo, float uc, const vec2& u, TransportMode mode) const override {
        return withEvalMueller(*this, sample(wo, uc, u, mode), wo, mode);
    }
    float pdf(const vec3& wo, const vec3& wi, TransportMode) const override {
        if (wo.z <= 0 || wi.z <= 0) return 0.0f;
        vec3 m = wo + wi;
        const float len = glm::length(m);
        if (len == 0) return 0.0f;
        m /= len;
        // Reflection Jacobian dωm/dωi = 1/(4 |wi·m|) (Walter et al. 2007 eq. 14; thesis eq. 2.22).
        return d_.pdf(wo, m) / (4.0f * std::abs(glm::dot(wo, m)));
    }
    std::optional<BSDFSample> sample(const vec3& wo, float, const vec2& u, TransportMode mode) const override {
        if (wo.z <= 0) return std::nullopt;
        const vec3 m = d_.sampleNormal(wo, u);
        const vec3 wi = reflect(wo, m);  // thesis 000 eq. 2.21
        if (wi.z <= 0) return std::nullopt;
        BSDFSample s;
        s.wi = wi;
        s.pdf = pdf(wo, wi, mode);
        if (!(s.pdf > 0)) return std::nullopt;
        s.f = eval(wo, wi, mode);
        s.flags = kBSDFReflection | kBSDFGlossy;
        return s;
    }
    uint32_t flags() const override { return kBSDFReflection | kBSDFGlossy; }

private:
    /// D G / (4 cos θi cos θo) at the half vector *m of (wo, wi) (thesis 000 eq. 2.6: f = F G D /
    /// (4 |wi·n| |wo·n|)), 0 below the surface or where D vanishes.
    float microfacetTerm(const vec3& wo, const vec3& wi, vec3* m) const {
        if (wo.z <= 0 || wi.z <= 0) return 0.0f;
        *m = wo + wi;
        const float len = glm::length(*m);
        if (len == 0) return 0.0f;
        *m /= len;
        const float D = d_.D(*m);
        if (D == 0) return 0.0f;
        const float G = d_.G(wi, wo, *m);
        return D * G / (4.0f * wi.z * wo.z);
    }
    SampledSpectrum fresnel(float cosI) const {
        return mirror_ ? SampledSpectrum(scale_.size(), 1.0f) : fresnelConductor(cosI, eta_, k_);
    }
    MicrofacetDistribution d_;
    SampledSpectrum eta_, k_, scale_;
    bool mirror_;
};

class RoughConductorMaterial final : public Material {
public:
    RoughConductorMaterial(MicrofacetParams mp, ConductorIOR c, SpectrumTexturePtr scale)
        : mp_(std::move(mp)), c_(std::move(c)), scale_(std::move(scale)) {}
    const BSDF* getBSDF(const ShadingPoint& sp, SampledWavelengths& wl, Arena& arena) const override {
        SampledSpectrum eta, k;
        c_.sample(wl, &eta, &k);
        return arena.make<RoughConductorBSDF>(mp_.at(sp.tex), eta, k, scale_->eval(sp.tex, wl), c_.mirror);
    }

private:
    MicrofacetParams mp_;
    ConductorIOR c_;
    SpectrumTexturePtr scale_;
};

std::shared_ptr<Material> createRoughConductor(const Properties& p) {
    MicrofacetParams mp = MicrofacetParams::read(p, "beckmann", 0.1f);
    ConductorIOR c = readConductor(p);
    for (const auto& [t, name] : {std::pair{mp.alphaU.get(), p.has("alpha_u") ? "alpha_u" : "alpha"},
                                  std::pair{mp.alphaV.get(), p.has("alpha_v") ? "alpha_v" : "alpha"}})
        if (t->isConstant() && !(t->eval({}) >= 0))
            failAt(p.locationOf(name), "roughconductor: ", name, " must be >= 0, got ", t->eval({}));
    return std::make_shared<RoughConductorMaterial>(
        std::move(mp), std::move(c), getSpectrumTexture(p, "specular_reflectance", SpectrumKind::Reflectance, 1.0f));
}

}  // namespace

IRIS_REGISTER(MaterialRegistry, "roughconductor", createRoughConductor);

}  // namespace iris
