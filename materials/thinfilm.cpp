// Thin-film interference on a smooth or rough interface (plugin "thinfilm"): a microfacet
// reflection lobe whose Fresnel term is the exact reflectance of a film stack (film + optional
// extra layers) over a conductor or dielectric substrate, at each path wavelength and at the
// microfacet angle (spectral/film_coating.h):
//   rough:  f(wo, wi) = R_stack(λ, wo·h) D(h) G(wi, wo, h) / (4 cosθo cosθi)   (Walter et al. 2007
//           eq. 20 with F replaced by the stack reflectance; thesis 000 eq. 2.6),
//   smooth: delta reflection with coefficient R_stack(λ, cosθo).
// Reflection only: for a dielectric substrate the transmitted energy is absorbed (the material is
// an opaque coated surface; docs/thin_film.md). One-sided (zero for wo.z <= 0).
#include "core/registry.h"
#include "materials/material.h"
#include "materials/microfacet.h"
#include "spectral/film_coating.h"

namespace iris {
namespace {

class ThinFilmBSDF final : public BSDF {
public:
    ThinFilmBSDF(const FilmCoating& coating, const MicrofacetDistribution& dist, bool smooth)
        : coating_(coating), dist_(dist), smooth_(smooth) {}

    SampledSpectrum eval(const vec3& wo, const vec3& wi, TransportMode) const override {
        const int n = coating_.size();
        if (smooth_ || wo.z <= 0 || wi.z <= 0) return SampledSpectrum(n);
        vec3 h = wo + wi;
        if (glm::dot(h, h) == 0) return SampledSpectrum(n);
        h = glm::normalize(h);
        const float woh = glm::dot(wo, h);
        if (woh <= 0) return SampledSpectrum(n);
        const float DG = dist_.D(h) * dist_.G(wi, wo, h);
        if (!(DG > 0)) return SampledSpectrum(n);
        return coating_.reflectance(woh) * (DG / (4.0f * wo.z * wi.z));
    }

    std::optional<BSDFSample> sample(const vec3& wo, float, const vec2& u, TransportMode mode) const override {
        if (wo.z <= 0) return std::nullopt;
        BSDFSample s;
        s.flags = kBSDFReflection | (smooth_ ? kBSDFSpecular : kBSDFGlossy);
        if (smooth_) {
            s.wi = reflectLocal(wo);
            s.pdf = 1.0f;
            s.f = coating_.reflectance(wo.z) / wo.z;
            return s;
        }
        const vec3 m = dist_.sampleNormal(wo, u);
        const float wom = glm::dot(wo, m);
        if (wom <= 0) return std::nullopt;
        s.wi = reflect(wo, m);
        if (s.wi.z <= 0) return std::nullopt;
        s.pdf = dist_.pdf(wo, m) / (4.0f * wom);  // half-vector → wi Jacobian (Walter 2007 eq. 14)
        if (!(s.pdf > 0)) return std::nullopt;
        s.f = eval(wo, s.wi, mode);
        return s;
    }

    float pdf(const vec3& wo, const vec3& wi, TransportMode) const override {
        if (smooth_ || wo.z <= 0 || wi.z <= 0) return 0.0f;
        const vec3 h = glm::normalize(wo + wi);
        const float woh = glm::dot(wo, h);
        if (woh <= 0) return 0.0f;
        return dist_.pdf(wo, h) / (4.0f * woh);
    }

    uint32_t flags() const override { return kBSDFReflection | (smooth_ ? kBSDFSpecular : kBSDFGlossy); }

private:
    FilmCoating coating_;
    MicrofacetDistribution dist_;
    bool smooth_;
};

class ThinFilmMaterial final : public Material {
public:
    ThinFilmMaterial(FilmCoatingSpec spec, MicrofacetDistribution dist, bool smooth)
        : spec_(std::move(spec)), dist_(dist), smooth_(smooth) {}

    const BSDF* getBSDF(const ShadingPoint& sp, SampledWavelengths& wl, Arena& arena) const override {
        return arena.make<ThinFilmBSDF>(FilmCoating(spec_, sp.tex, wl, arena), dist_, smooth_);
    }

private:
    FilmCoatingSpec spec_;
    MicrofacetDistribution dist_;
    bool smooth_;
};

std::shared_ptr<Material> createThinFilm(const Properties& p) {
    const std::string substrate = p.getString("substrate", "conductor");
    float defEta, defK;
    if (substrate == "conductor") {
        defEta = 0.13f;  // silver-like constants (Ag at 550 nm ≈ 0.13 + 3.3i); give measured spectra for real metals
        defK = 3.3f;
    } else if (substrate == "dielectric") {
        defEta = 1.5f;
        defK = 0.0f;
    } else {
        failAt(p.locationOf("substrate"), "substrate must be 'conductor' or 'dielectric', got '", substrate, "'");
    }
    FilmCoatingSpec spec = FilmCoatingSpec::fromProperties(p, defEta, defK);
    const MicrofacetType type = MicrofacetDistribution::parseType(p.getString("distribution", "ggx"));
    const float alpha = p.getFloat("alpha", 0.0f);
    const float au = p.getFloat("alpha_u", alpha), av = p.getFloat("alpha_v", alpha);
    if (!(au >= 0) || !(av >= 0)) failAt(p.location(), "roughness alpha must be >= 0");
    const bool smooth = au == 0 && av == 0;
    if (smooth != (au == 0 || av == 0)) failAt(p.location(), "alpha_u and alpha_v must both be 0 (smooth) or both > 0");
    const bool visible = p.getBool("sample_visible", true);
    return std::make_shared<ThinFilmMaterial>(std::move(spec), MicrofacetDistribution(type, au, av, visible), smooth);
}

}  // namespace

IRIS_REGISTER(MaterialRegistry, "thinfilm", createThinFilm);

}  // namespace iris
