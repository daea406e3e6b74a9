// Rough dielectric interface: microfacet reflection and refraction of Walter, Marschner, Li and
// Torrance 2007 ("Microfacet Models for Refraction through Rough Surfaces"), thesis 000 §2.3.2:
//   f_r = F D G / (4 |cosθi cosθo|)                                          (thesis eq. 2.6)
//   f_t = |wi·m||wo·m| / (|cosθi||cosθo|) · η_o² (1 − F) G D / (η_i (wi·m) + η_o (wo·m))²
//                                                          (Walter eq. 21, thesis eqs. 2.15–2.16)
// with the generalised half vector m ∝ −(η_i wi + η_o wo) (Walter eq. 16); here η_o is the index
// on the viewer's (wo) side, which makes f_t the radiance BTDF; Importance mode is its adjoint,
// f(wi, wo): η_i² instead of η_o², and per-channel Fresnel factors seen from wi (materials/fresnel.h).
// Sampling (Walter §5.3, thesis eqs. 2.19–2.22): m from the (visible) normal distribution, then
// reflection with probability F(wo·m) else refraction; pdf = pm(m) · {F/(4|wo·m|) ,
// (1−F) η_i²|wi·m| / (η_o (wo·m) + η_i (wi·m))²} (Walter eqs. 14, 17).
// Mitsuba 3 plugin "roughdielectric": distribution ("beckmann"), alpha (0.1), alpha_u/alpha_v,
// sample_visible (true), int_ior ("bk7"), ext_ior ("air") (spectral/ior_params.h), specular_reflectance,
// specular_transmittance (1); plus masking / beckmann_rational_g1 (materials/microfacet.h).
// Wavelength dependence as in "dielectric": one η (hero or green channel) decides m and the
// Jacobians; the Fresnel factor uses each channel's own η.
#include "core/registry.h"
#include "materials/fresnel.h"
#include "materials/fresnel_mueller.h"
#include "materials/material.h"
#include "materials/microfacet.h"
#include "materials/textures/texture_params.h"
#include "spectral/ior_params.h"

namespace iris {
namespace {

class RoughDielectricBSDF final : public BSDF {
public:
    RoughDielectricBSDF(const MicrofacetDistribution& d, const SampledSpectrum& eta, float etaDir,
                        const SampledSpectrum& r, const SampledSpectrum& t)
        : d_(d), eta_(eta), etaDir_(etaDir), r_(r), t_(t) {}

    SampledSpectrum eval(const vec3& wo, const vec3& wi, TransportMode mode) const override {
        const int n = r_.size();
        Geometry g;
        const float v = lobeTerm(wo, wi, mode, &g);
        if (v == 0) return SampledSpectrum(n);
        const SampledSpectrum F = fresnelDielectric(g.dotO, eta_);
        if (g.reflect) return F * r_ * v;
        // Walter eq. 21 with η_o (viewer side) = 1 and η_i = etaW relative to it (lobeTerm); its
        // adjoint f(wi, wo) has η_i² instead of η_o² and each channel's Fresnel factor seen from wi.
        if (mode == TransportMode::Radiance) return (1.0f - F) * t_ * v;
        return (1.0f - fresnelDielectricAdjoint(g.dotO, g.dotI, eta_, etaDir_)) * t_ * v;
    }
    /// Polarized: the microfacet's Fresnel reflection or refraction matrix (the pattern of Mitsuba 3
    /// roughconductor.cpp and dielectric.cpp; Mitsuba 3's own roughdielectric depolarizes,
    /// docs/polarization.md).
    MuellerSpectrum evalMueller(const vec3& wo, const vec3& wi, TransportMode mode) const override {
        Geometry g;
        const float v = lobeTerm(wo, wi, mode, &g);
        if (v == 0) return MuellerSpectrum::depolarizer(SampledSpectrum(r_.size()));
        if (g.reflect) return fresnelReflectionMueller(g.m, wi, wo, eta_) * (r_ * v);
        return fresnelTransmissionMueller(g.m, wi, wo, eta_) * (t_ * v);
    }
    std::optional<PolarizedBSDFSample> sampleMueller(const vec3& wo, float uc, const vec2& u, TransportMode mode) const override {
        return withEvalMueller(*this, sample(wo, uc, u, mode), wo, mode);
    }

    float pdf(const vec3& wo, const vec3& wi, TransportMode) const override {
        Geometry g;
        if (!geometry(wo, wi, &g)) return 0.0f;
        const float pm = d_.pdf(wo, g.m);
        const float R = fresnelDielectric(g.dotO, etaDir_);
        if (g.reflect) return R * pm / (4.0f * std::abs(g.dotO));
        return (1.0f - R) * pm * sqr(g.etaW) * std::abs(g.dotI) / sqr(g.dotO + g.etaW * g.dotI);
    }

    std::optional<BSDFSample> sample(const vec3& wo, float uc, const vec2& u, TransportMode mode) const override {
        if (wo.z == 0) return std::nullopt;
        const vec3 m = d_.sampleNormal(wo, u);  // m.z > 0
        const float dotO = glm::dot(wo, m);
        if (dotO * wo.z <= 0) return std::nullopt;  // back-facing microfacet (all-normals sampling)
        const FresnelDielectricResult fr = fresnelDielectricFull(dotO, etaDir_);
        BSDFSample s;
        if (uc < fr.R) {
            s.wi = reflect(wo, m);
            if (s.wi.z * wo.z <= 0) return std::nullopt;
            s.flags = kBSDFReflection | kBSDFGlossy;
        } else {
            s.wi = glm::normalize(refract(wo, m, fr.cosThetaT, fr.etaTI));
            if (s.wi.z * wo.z >= 0) return std::nullopt;
            s.flags = kBSDFTransmission | kBSDFGlossy;
            s.eta = fr.etaIT;
        }
        s.pdf = pdf(wo, s.wi, mode);
        if (!(s.pdf > 0)) return std::nullopt;
        s.f = eval(wo, s.wi, mode);
        return s;
    }

    uint32_t flags() const override { return kBSDFReflection | kBSDFTransmission | kBSDFGlossy; }

private:
    struct Geometry {
        vec3 m;
        float dotO, dotI, etaW;
        bool reflect;
    };
    /// f without its Fresnel factor and weights: D G / (4 |cos θi cos θo|) for reflection, Walter
    /// eq. 21's rest with η_o (viewer side) = 1 and η_i = etaW relative to it for refraction; 0
    /// where the pair has no valid half vector or D vanishes.
    float lobeTerm(const vec3& wo, const vec3& wi, TransportMode mode, Geometry* g) const {
        if (!geometry(wo, wi, g)) return 0.0f;
        const float D = d_.D(g->m);
        if (D == 0) return 0.0f;
        const float G = d_.G(wi, wo, g->m);
        if (g->reflect) return D * G / (4.0f * std::abs(wi.z * wo.z));
        float v = D * G * std::abs(g->dotO * g->dotI) / (std::abs(wi.z * wo.z) * sqr(g->dotO + g->etaW * g->dotI));
        if (mode == TransportMode::Importance) v *= sqr(g->etaW);
        return v;
    }
    /// The (generalised) half vector of (wo, wi), oriented to +z, and the side checks.
    bool geometry(const vec3& wo, const vec3& wi, Geometry* g) const {
        if (wo.z == 0 || wi.z == 0) return false;
        g->reflect = wo.z * wi.z > 0;
        // η of wi's side relative to wo's side.
        g->etaW = g->reflect ? 1.0f : (wo.z > 0 ? etaDir_ : 1.0f / etaDir_);
        vec3 m = wo + wi * g->etaW;  // Walter eq. 16 (reflection: eq. 13)
        const float len = glm::length(m);
        if (!(len > 0)) return false;
        m /= len;
        if (m.z < 0) m = -m;
        if (m.z == 0) return false;
        g->m = m;
        g->dotO = glm::dot(wo, m);
        g->dotI = glm::dot(wi, m);
        // Both directions must see the front of the microfacet on their own side.
        if (g->dotO * wo.z <= 0 || g->dotI * wi.z <= 0) return false;
        return true;
    }

    MicrofacetDistribution d_;
    SampledSpectrum eta_;
    float etaDir_;
    SampledSpectrum r_, t_;
};

class RoughDielectricMaterial final : public Material {
public:
    RoughDielectricMaterial(MicrofacetParams mp, IOR in, IOR ext, SpectrumTexturePtr r, SpectrumTexturePtr t)
        : mp_(std::move(mp)), in_(std::move(in)), ext_(std::move(ext)), r_(std::move(r)), t_(std::move(t)) {}
    const BSDF* getBSDF(const ShadingPoint& sp, SampledWavelengths& wl, Arena& arena) const override {
        SampledSpectrum eta;
        const float etaDir = relativeIOR(in_, ext_, wl, &eta);
        return arena.make<RoughDielectricBSDF>(mp_.at(sp.tex), eta, etaDir, r_->eval(sp.tex, wl), t_->eval(sp.tex, wl));
    }

private:
    MicrofacetParams mp_;
    IOR in_, ext_;
    SpectrumTexturePtr r_, t_;
};

std::shared_ptr<Material> createRoughDielectric(const Properties& p) {
    MicrofacetParams mp = MicrofacetParams::read(p, "beckmann", 0.1f);
    auto [in, ext] = readInterfaceIOR(p);
    for (const auto& [t, name] : {std::pair{mp.alphaU.get(), p.has("alpha_u") ? "alpha_u" : "alpha"},
                                  std::pair{mp.alphaV.get(), p.has("alpha_v") ? "alpha_v" : "alpha"}})
        if (t->isConstant() && !(t->eval({}) >= 0))
            failAt(p.locationOf(name), "roughdielectric: ", name, " must be >= 0, got ", t->eval({}));
    return std::make_shared<RoughDielectricMaterial>(
        std::move(mp), std::move(in), std::move(ext),
        getSpectrumTexture(p, "specular_reflectance", SpectrumKind::Reflectance, 1.0f),
        getSpectrumTexture(p, "specular_transmittance", SpectrumKind::Reflectance, 1.0f));
}

}  // namespace

IRIS_REGISTER(MaterialRegistry, "roughdielectric", createRoughDielectric);

}  // namespace iris
