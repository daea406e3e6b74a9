// A thin-film coating over a Lambertian base (plugin "iridescent_diffuse"): exterior (ext_ior) /
// film stack / clear binder of index int_ior / diffuse base of albedo ρ (`reflectance`).
//
//   specular:  the film stack's reflectance R(λ, ·) on a smooth interface (delta lobe) or on
//              microfacets (R at wo·h, D G / (4 cosθo cosθi), Walter et al. 2007);
//   diffuse:   f_d = ρ T(λ, θi) T(λ, θo) / (π η² (1 − ρ r_int(λ)))
//              — the plastic model of Weidlich & Wilkie 2007 / Mitsuba's smooth plastic (Jakob,
//              Mitsuba documentation "plastic"), with the interface transmittances (1 − F)
//              replaced by the stack's transmittance T (film absorption included, T reciprocal)
//              and the internal reflectance of the binder side replaced by the stack's
//              hemispherical reflectance from below r_int (ThinFilmCoating::
//              internalHemisphericalReflectance, Gauss–Legendre quadrature per wavelength;
//              tabulated at construction for a constant thickness, see ThinFilmCoatingSpec::RintCache).
//              The internal bounces between base and film are summed incoherently (the binder is
//              thick), the 1/η² accounts for the radiance compression inside the binder.
// For the rough coat the diffuse term uses the same macro-surface T and r_int (the smooth-coat
// approximation, as Mitsuba's roughplastic does with Fresnel); see docs/thin_film.md.
// Sampling: the specular lobe with probability ps = R̄ / (R̄ + T̄ ρ̄) (clamped to [0.05, 0.95]),
// else cosine-weighted. One-sided.
#include "core/registry.h"
#include "core/sampling.h"
#include "materials/material.h"
#include "materials/microfacet.h"
#include "materials/thin_film_coating.h"
#include "materials/fresnel_mueller.h"
#include "materials/thin_film_mueller.h"
#include "materials/textures/texture_params.h"

#include <limits>

namespace iris {
namespace {

class IridescentDiffuseBSDF final : public BSDF {
public:
    IridescentDiffuseBSDF(const ThinFilmCoatingArgs& c, const SampledSpectrum& rho, const MicrofacetDistribution& dist,
                          bool smooth)
        : coating_(c.spec, c.tex, c.wl, c.arena), dist_(dist), smooth_(smooth) {
        const int n = coating_.size();
        // Diffuse base factor ρ / (π η² (1 − ρ r_int)) per wavelength.
        base_ = SampledSpectrum(n);
        for (int k = 0; k < n; ++k) {
            const double eta = coating_.substrateIor(k).real() / coating_.extIor();
            const double rint = coating_.internalHemisphericalReflectance(k);
            const double denom = 1.0 - rho[k] * rint;
            base_[k] = denom > 0 ? float(rho[k] / (3.14159265358979323846 * eta * eta * denom)) : 0.0f;
        }
        rhoAvg_ = rho.average();
    }

    SampledSpectrum eval(const vec3& wo, const vec3& wi, TransportMode) const override {
        const int n = coating_.size();
        if (wo.z <= 0 || wi.z <= 0) return SampledSpectrum(n);
        SampledSpectrum f = diffuse(wo, wi);
        if (!smooth_) f += specular(wo, wi);
        return f;
    }

    std::optional<BSDFSample> sample(const vec3& wo, float uc, const vec2& u, TransportMode mode) const override {
        if (wo.z <= 0) return std::nullopt;
        const float ps = specularProbability(wo);
        BSDFSample s;
        if (uc < ps) {
            if (smooth_) {
                s.wi = reflectLocal(wo);
                s.pdf = ps;
                // R(wo.z) of the cached pair equals coating_.reflectance(wo.z): the binder (the
                // stack's substrate) is real here, so no Belcour–Barla T override applies.
                s.f = woTerms(wo.z).R / wo.z;
                s.flags = kBSDFReflection | kBSDFSpecular;
                return s;
            }
            const auto r = sampleMicrofacetReflection(dist_, wo, u);
            if (!r) return std::nullopt;
            s.wi = r->wi;
            s.flags = kBSDFReflection | kBSDFGlossy;
            s.pdf = ps * r->pdfM / (4.0f * r->wom) + (1.0f - ps) * cosineHemispherePdf(s.wi.z);
            if (!(s.pdf > 0)) return std::nullopt;
            s.f = diffuse(wo, s.wi) + coating_.reflectance(r->wom) * (r->DG / (4.0f * wo.z * s.wi.z));
            return s;
        }
        s.wi = sampleCosineHemisphere(u);
        s.flags = kBSDFReflection | kBSDFDiffuse;
        if (s.wi.z <= 0) return std::nullopt;
        s.pdf = pdfWith(wo, s.wi, ps);
        if (!(s.pdf > 0)) return std::nullopt;
        s.f = eval(wo, s.wi, mode);
        return s;
    }

    float pdf(const vec3& wo, const vec3& wi, TransportMode) const override {
        if (wo.z <= 0 || wi.z <= 0) return 0.0f;
        return pdfWith(wo, wi, specularProbability(wo));
    }

    uint32_t flags() const override {
        return kBSDFReflection | kBSDFDiffuse | (smooth_ ? kBSDFSpecular : kBSDFGlossy);
    }

    /// Polarized: the diffuse lobe enters and leaves through the stack around a depolarizing base
    /// (materials/thin_film_mueller.h coatingDiffuseMueller), the specular lobe is the stack's
    /// reflection matrix.
    MuellerSpectrum evalMueller(const vec3& wo, const vec3& wi, TransportMode) const override {
        const int n = coating_.size();
        if (wo.z <= 0 || wi.z <= 0) return MuellerSpectrum::depolarizer(SampledSpectrum(n));
        MuellerSpectrum M = coatingDiffuseMueller(coating_, base_, wi, wo);
        if (smooth_) return M;
        const vec3 h = glm::normalize(wo + wi);
        const float woh = glm::dot(wo, h);
        const float DG = woh > 0 ? dist_.D(h) * dist_.G(wi, wo, h) : 0.0f;
        if (DG > 0) M += coatingReflectionMueller(coating_, woh, false, h, wi, wo) * (DG / (4.0f * wo.z * wi.z));
        return M;
    }
    std::optional<PolarizedBSDFSample> sampleMueller(const vec3& wo, float uc, const vec2& u, TransportMode mode) const override {
        const std::optional<BSDFSample> s = sample(wo, uc, u, mode);
        if (!s || !s->isSpecular()) return withEvalMueller(*this, s, wo, mode);
        return withMueller(s, coatingReflectionMueller(coating_, wo.z, false, vec3(0, 0, 1), s->wi, wo),
                           SampledSpectrum(coating_.size(), 1.0f / wo.z));
    }

private:
    SampledSpectrum diffuse(const vec3& wo, const vec3& wi) const {
        SampledSpectrum Ri, Ti;
        coating_.reflectanceTransmittance(wi.z, Ri, Ti);
        return base_ * Ti * woTerms(wo.z).T;
    }

    /// The stack's R and T at cosθo. A path tracer asks for them several times per vertex with the
    /// same wo (eval and pdf of light sampling, then sample, which evaluates again): they are
    /// computed once per distinct wo.z and reused (identical values; the BSDF belongs to one path,
    /// hence to one thread).
    struct StackRT {
        SampledSpectrum R, T;
    };
    const StackRT& woTerms(float cosThetaO) const {
        if (!(cosThetaO == woZ_)) {  // also recomputes for NaN
            coating_.reflectanceTransmittance(cosThetaO, wo_.R, wo_.T);
            woZ_ = cosThetaO;
        }
        return wo_;
    }

    SampledSpectrum specular(const vec3& wo, const vec3& wi) const {
        const int n = coating_.size();
        const vec3 h = glm::normalize(wo + wi);
        const float woh = glm::dot(wo, h);
        if (woh <= 0) return SampledSpectrum(n);
        const float DG = dist_.D(h) * dist_.G(wi, wo, h);
        if (!(DG > 0)) return SampledSpectrum(n);
        return coating_.reflectance(woh) * (DG / (4.0f * wo.z * wi.z));
    }

    float specularProbability(const vec3& wo) const {
        const StackRT& rt = woTerms(wo.z);
        const float r = rt.R.average(), t = rt.T.average() * rhoAvg_;
        if (r + t <= 0) return 0.5f;
        if (t == 0) return 1.0f;
        if (r == 0) return 0.0f;
        return std::clamp(r / (r + t), 0.05f, 0.95f);
    }

    float pdfWith(const vec3& wo, const vec3& wi, float ps) const {
        float p = (1.0f - ps) * cosineHemispherePdf(wi.z);
        if (!smooth_) {
            const vec3 h = glm::normalize(wo + wi);
            const float woh = glm::dot(wo, h);
            if (woh > 0) p += ps * dist_.pdf(wo, h) / (4.0f * woh);
        }
        return p;
    }

    ThinFilmCoating coating_;
    SampledSpectrum base_;
    float rhoAvg_ = 0;
    mutable float woZ_ = std::numeric_limits<float>::quiet_NaN();
    mutable StackRT wo_;
    MicrofacetDistribution dist_;
    bool smooth_;
};

class IridescentDiffuseMaterial final : public Material {
public:
    IridescentDiffuseMaterial(ThinFilmCoatingSpec spec, SpectrumTexturePtr rho, MicrofacetDistribution dist, bool smooth)
        : spec_(std::move(spec)), rho_(std::move(rho)), dist_(dist), smooth_(smooth) {}

    const BSDF* getBSDF(const ShadingPoint& sp, SampledWavelengths& wl, Arena& arena) const override {
        const SampledSpectrum rho = map(rho_->eval(sp.tex, wl), [](float x) { return std::clamp(x, 0.0f, 1.0f); });
        return arena.make<IridescentDiffuseBSDF>(ThinFilmCoatingArgs{spec_, sp.tex, wl, arena}, rho, dist_, smooth_);
    }

private:
    ThinFilmCoatingSpec spec_;
    SpectrumTexturePtr rho_;
    MicrofacetDistribution dist_;
    bool smooth_;
};

std::shared_ptr<Material> createIridescentDiffuse(const Properties& p) {
    ThinFilmCoatingSpec spec = ThinFilmCoatingSpec::fromProperties(p, 1.5f, 0.0f, 300.0f, "int_ior", nullptr);
    // The truncated sum loops over `bounces` per evaluation: an absurd count would hang the render.
    if (spec.bounces > 1000)
        failAt(p.locationOf("bounces"), "iridescent_diffuse: bounces must be in [0, 1000], got ", spec.bounces);
    if (p.getBool("cache_internal_reflectance", true)) spec.precomputeInternalReflectance();
    SpectrumTexturePtr rho = getSpectrumTexture(p, "reflectance", SpectrumKind::Reflectance, 0.5f);
    const MicrofacetType type = MicrofacetDistribution::parseType(p.getString("distribution", "ggx"));
    const float alpha = p.getFloat("alpha", 0.0f);
    if (!(alpha >= 0)) failAt(p.locationOf("alpha"), "alpha must be >= 0, got ", alpha);
    const bool visible = p.getBool("sample_visible", true);
    return std::make_shared<IridescentDiffuseMaterial>(std::move(spec), std::move(rho),
                                                       MicrofacetDistribution(type, alpha, alpha, visible), alpha == 0);
}

}  // namespace

IRIS_REGISTER(MaterialRegistry, "iridescent_diffuse", createIridescentDiffuse);

}  // namespace iris
