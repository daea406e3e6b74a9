// Polarized plastic (Mitsuba 3 "pplastic", src/bsdfs/pplastic.cpp and its plugin documentation
// "Polarized plastic material"): the pBRDF of Baek, Jeon, Tong & Kim 2018, "Simultaneous
// Acquisition of Polarimetric SVBRDF and Normals" (ACM TOG 37(6), SIGGRAPH Asia), §4: the sum of
//   specular  a microfacet lobe whose facets reflect with the polarized Fresnel matrix,
//             ks F(wi·h) D(h) G(wo, wi, h) / (4 cos θo cos θi);
//   diffuse   light refracted into the surface (polarized Fresnel transmission T at θi), scattered
//             by a depolarizing Lambertian base ρ/π, refracted out (T at θo):
//             ρ (1 − F(cos θi)) (1 − F(cos θo)) / π for unpolarized light.
// Unlike `plastic` and `roughplastic` the two are added "in a more ad-hoc way" (Mitsuba's doc): no
// internal reflections, no 1/η² — the sum loses energy but never gains any. The diffuse lobe's
// outgoing refraction polarizes its light weakly along p, the specular lobe's along s (the 90°
// flip shape-from-polarization uses; Mitsuba's doc). docs/polarization.md lists the matrix.
//
// Parameters (Mitsuba 3's names and defaults):
//   diffuse_reflectance   spectrum | texture, ρ                        default 0.5
//   specular_reflectance  spectrum | texture, ks                       default 1.0
//   int_ior, ext_ior      float | preset name; η = int/ext, > 0, ≠ 1    default 1.49, 1.000277
//   eta                   float, η directly (Mitsuba 3 exposes η under this name; an iris
//                         shorthand here, instead of int_ior/ext_ior)
//   distribution          "beckmann" | "ggx"                           default beckmann
//   alpha | alpha_u, alpha_v  float ≥ 0 (Mitsuba clamps to 1e-4)      default 0.1
//   sample_visible        bool                                          default true
#include "core/registry.h"
#include "materials/fresnel.h"
#include "materials/fresnel_mueller.h"
#include "materials/fresnel_polarized.h"
#include "materials/material.h"
#include "materials/microfacet.h"
#include "materials/textures/texture_params.h"
#include "materials/thesis_rough_coat.h"
#include "spectral/ior_params.h"
#include "spectral/stokes_basis.h"

namespace iris {
namespace {

/// The s axis of the plane of incidence of direction d about the normal +z, or (1, 0, 0) when d is
/// along the normal (Mitsuba 3 pplastic's handle_singularity, per side).
vec3 sAxisAboutNormal(const vec3& d) {
    const vec3 s = glm::cross(vec3(0, 0, 1), d);
    const float l2 = glm::dot(s, s);
    return l2 > 0 ? s / std::sqrt(l2) : vec3(1, 0, 0);
}

/// The diffuse lobe's Mueller matrix without ρ/π, in s-axis bases: T_out · depolarizer · T_in
/// (Mitsuba 3 pplastic.cpp, "diff = Ti * diff * To"; Baek et al. 2018 §4, diffuse pBRDF). The
/// depolarizer keeps only T_in's first row (A_i, B_i, 0, 0) and T_out's first column
/// (A_o, B_o, 0, 0), so the product is their outer product. T_out is the transmission from inside
/// at the refracted angle θt with index 1/η, which by the Stokes relations t t' = 1 − r² (Born &
/// Wolf §1.6.1) has the power transmittances of the transmission from outside at θo with index η.
MuellerSpectrum diffuseTransmissionMueller(const vec3& wo, const vec3& wi, float eta, int n) {
    const InterfaceMuellerTerms in = transmissionTerms(wi.z, eta), out = transmissionTerms(wo.z, eta);
    const float a[2] = {out.A, out.B}, b[2] = {in.A, in.B};
    MuellerSpectrum m(n);
    for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j) m(i, j) = SampledSpectrum(n, a[i] * b[j]);
    // Light arrives along −wi and leaves along wo; s axes n × (−wi) and n × wo (Mitsuba 3 pplastic).
    return toImplicitBases(m, -wi, sAxisAboutNormal(-wi), wo, sAxisAboutNormal(wo));
}

class PolarizedPlasticBSDF final : public BSDF {
public:
    PolarizedPlasticBSDF(const MicrofacetDistribution& dist, float eta, const SampledSpectrum& ks, const SampledSpectrum& rho)
        : dist_(dist), eta_(eta), ks_(ks), rho_(rho) {
        // Mitsuba 3: specular sampling weight s_mean / (d_mean + s_mean) of the textures' means;
        // here the lane means at this point (a sampling choice only: the estimate is unbiased).
        const float s = ks.average(), d = rho.average();
        ps_ = s + d > 0 ? s / (s + d) : 0.5f;
    }

    /// The diffuse lobe's unpolarized value without ρ: (1 − F(μi)) (1 − F(μo)) / π (Mitsuba 3
    /// pplastic.cpp, unpolarized eval; Baek et al. 2018 §4).
    float diffuse(const vec3& wo, const vec3& wi) const {
        return (1.0f - fresnelDielectric(wi.z, eta_)) * (1.0f - fresnelDielectric(wo.z, eta_)) * kInvPi;
    }

    SampledSpectrum eval(const vec3& wo, const vec3& wi, TransportMode) const override {
        SampledSpectrum f(ks_.size());
        if (wo.z <= 0 || wi.z <= 0) return f;
        // Specular: ks F(wo·h) D G / (4 cos θo cos θi) (Walter et al. 2007 eq. 20; Mitsuba 3 pplastic).
        const float s = roughCoatSpecular(roughCoatGeometry(dist_, wo, wi), wo, eta_);
        const float d = diffuse(wo, wi);
        for (int c = 0; c < f.size(); ++c) f[c] = ks_[c] * s + rho_[c] * d;
        return f;
    }

    /// Polarized (Mitsuba 3 pplastic.cpp, polarized eval, radiance transport): the microfacet's
    /// Fresnel reflection matrix at h times ks D G / (4 cos θo cos θi), plus ρ/π times the diffuse
    /// lobe's transmission matrices (diffuseTransmissionMueller).
    MuellerSpectrum evalMueller(const vec3& wo, const vec3& wi, TransportMode) const override {
        const int n = ks_.size();
        if (wo.z <= 0 || wi.z <= 0) return MuellerSpectrum::depolarizer(SampledSpectrum(n));
        MuellerSpectrum M = diffuseTransmissionMueller(wo, wi, eta_, n) * (rho_ * kInvPi);
        const RoughCoatGeometry g = roughCoatGeometry(dist_, wo, wi);
        if (g.dg > 0) M += fresnelReflectionMueller(g.h, wi, wo, SampledSpectrum(n, eta_)) * (ks_ * g.dg);
        return M;
    }
    std::optional<PolarizedBSDFSample> sampleMueller(const vec3& wo, float uc, const vec2& u, TransportMode mode) const override {
        return withEvalMueller(*this, sample(wo, uc, u, mode), wo, mode);
    }

    std::optional<BSDFSample> sample(const vec3& wo, float uc, const vec2& u, TransportMode mode) const override {
        if (wo.z <= 0) return std::nullopt;
        const bool specular = uc < ps_;
        const vec3 wi = specular ? reflect(wo, dist_.sampleNormal(wo, u)) : sampleCosineHemisphere(u);
        if (wi.z <= 0) return std::nullopt;
        return sampleFromEval(wo, wi, kBSDFReflection | (specular ? kBSDFGlossy : kBSDFDiffuse), mode);
    }

    /// The mixture's density (Mitsuba 3 pplastic.cpp pdf): the microfacet reflection's D G1 / (4 cos θo)
    /// with visible normals, and the cosine hemisphere.
    float pdf(const vec3& wo, const vec3& wi, TransportMode) const override {
        if (wo.z <= 0 || wi.z <= 0) return 0.0f;
        return ps_ * roughCoatSpecularPdf(dist_, wo, wi) + (1.0f - ps_) * cosineHemispherePdf(wi.z);
    }

    uint32_t flags() const override { return kBSDFReflection | kBSDFGlossy | kBSDFDiffuse; }

private:
    MicrofacetDistribution dist_;
    float eta_, ps_ = 0.5f;
    SampledSpectrum ks_, rho_;
};

/// η from `eta` or from int_ior / ext_ior (Mitsuba 3's defaults "polypropylene" and "air"); it must
/// be > 0 and ≠ 1 (Mitsuba 3 pplastic: "indices of refraction must be positive and differ").
float readRelativeIOR(const Properties& p) {
    if (p.has("eta") && (p.has("int_ior") || p.has("ext_ior")))
        failAt(p.locationOf("eta"), "pplastic: give either 'eta' or 'int_ior'/'ext_ior', not both");
    const bool direct = p.has("eta");
    const float eta = direct ? p.getFloat("eta", 1.5f)
                             : readConstantIOR(p, "int_ior", 1.49f) / readConstantIOR(p, "ext_ior", 1.000277f);
    const SourceLocation loc = direct ? p.locationOf("eta") : p.has("int_ior") ? p.locationOf("int_ior") : p.location();
    if (!(eta > 0) || !std::isfinite(eta)) failAt(loc, "pplastic: the relative index eta must be > 0, got ", eta);
    if (eta == 1.0f) failAt(loc, "pplastic: the interior and exterior indices must differ (eta = 1)");
    return eta;
}

/// A constant roughness must be ≥ 0 (Mitsuba 3 clamps 0 to 1e-4, as MicrofacetDistribution does here).
void checkAlpha(const Properties& p, const FloatTexturePtr& a, const char* name) {
    const auto* c = dynamic_cast<const ConstantFloatTexture*>(a.get());
    if (c && !(c->value() >= 0 && std::isfinite(c->value())))
        failAt(p.has(name) ? p.locationOf(name) : p.location(), "pplastic: ", name, " must be >= 0, got ", c->value());
}

class PolarizedPlasticMaterial final : public Material {
public:
    explicit PolarizedPlasticMaterial(const Properties& p) : mf_(MicrofacetParams::read(p)) {
        checkAlpha(p, mf_.alphaU, p.has("alpha_u") ? "alpha_u" : "alpha");
        checkAlpha(p, mf_.alphaV, p.has("alpha_v") ? "alpha_v" : "alpha");
        eta_ = readRelativeIOR(p);
        rho_ = getSpectrumTexture(p, "diffuse_reflectance", SpectrumKind::Reflectance, 0.5f);
        ks_ = getSpectrumTexture(p, "specular_reflectance", SpectrumKind::Reflectance, 1.0f);
    }

    const BSDF* getBSDF(const ShadingPoint& sp, SampledWavelengths& wl, Arena& arena) const override {
        return arena.make<PolarizedPlasticBSDF>(mf_.at(sp.tex), eta_, clampZero(ks_->eval(sp.tex, wl)),
                                                clampZero(rho_->eval(sp.tex, wl)));
    }

private:
    MicrofacetParams mf_;
    float eta_ = 1.5f;
    SpectrumTexturePtr rho_, ks_;
};

std::shared_ptr<Material> createPolarizedPlastic(const Properties& p) { return std::make_shared<PolarizedPlasticMaterial>(p); }

}  // namespace

IRIS_REGISTER(MaterialRegistry, "pplastic", createPolarizedPlastic);

}  // namespace iris
