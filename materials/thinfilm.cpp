// Thin-film interference on a smooth or rough interface (plugin "thinfilm"): a microfacet
// reflection lobe whose Fresnel term is the exact reflectance of a film stack (film + optional
// extra layers) over a conductor or dielectric substrate, at each path wavelength and at the
// microfacet angle (spectral/film_coating.h):
//   rough:  f(wo, wi) = R_stack(λ, wo·h) D(h) G(wi, wo, h) / (4 cosθo cosθi)   (Walter et al. 2007
//           eq. 20 with F replaced by the stack reflectance; thesis 000 eq. 2.6),
//   smooth: delta reflection with coefficient R_stack(λ, cosθo).
// Default: reflection only, one-sided (zero for wo.z <= 0); for a dielectric substrate the
// transmitted energy is absorbed (an opaque coated surface; docs/thin_film.md).
// `transmission` = true (smooth, non-absorbing, non-dispersive dielectric substrate only): a
// two-sided interface between the exterior and the substrate medium with delta reflection R and
// delta refraction T of the stack, lit from either side (from below: the reversed stack), the
// refracted direction by Snell's law between ext_ior and substrate_eta (the film's parallel layers
// do not change it); radiance transport scales the refracted lobe by 1/η² (pbrt-v4 §9.5.2).
// substrate_eta = ext_ior gives a free-standing film (soap bubble): light passes straight through.
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

/// Smooth film on a dielectric with both reflection and transmission (see the file comment).
class ThinFilmTransmissionBSDF final : public BSDF {
public:
    explicit ThinFilmTransmissionBSDF(const FilmCoating& coating) : coating_(coating) {}

    SampledSpectrum eval(const vec3&, const vec3&, TransportMode) const override {
        return SampledSpectrum(coating_.size());
    }
    float pdf(const vec3&, const vec3&, TransportMode) const override { return 0.0f; }
    uint32_t flags() const override { return kBSDFReflection | kBSDFTransmission | kBSDFSpecular; }

    std::optional<BSDFSample> sample(const vec3& wo, float uc, const vec2&, TransportMode mode) const override {
        if (wo.z == 0) return std::nullopt;
        const bool outside = wo.z > 0;
        const float c = std::abs(wo.z);
        SampledSpectrum R, T;
        if (outside) coating_.reflectanceTransmittance(c, R, T);
        else coating_.fromBelowRT(c, R, T);
        const float r = R.average(), t = T.average();
        if (r + t <= 0) return std::nullopt;  // everything absorbed
        const float pR = r / (r + t);
        BSDFSample s;
        if (uc < pR) {
            s.wi = reflectLocal(wo);
            s.pdf = pR;
            s.f = R / c;
            s.flags = kBSDFReflection | kBSDFSpecular;
            return s;
        }
        // Snell between the exterior and the substrate (indices constant over λ, checked at load).
        const float etaIT = outside ? float(coating_.substrateIor(0).real() / coating_.extIor())
                                    : float(coating_.extIor() / coating_.substrateIor(0).real());  // n_t / n_i
        const float sin2T = (1.0f - c * c) / (etaIT * etaIT);
        if (sin2T >= 1.0f) return std::nullopt;  // T = 0 there; not reached since t > 0 needs sin2T < 1
        const float cT = std::sqrt(1.0f - sin2T);
        s.wi = vec3(-wo.x / etaIT, -wo.y / etaIT, outside ? -cT : cT);
        s.pdf = 1.0f - pR;
        s.f = T / cT;
        if (mode == TransportMode::Radiance) s.f /= etaIT * etaIT;
        s.eta = etaIT;
        s.flags = kBSDFTransmission | kBSDFSpecular;
        return s;
    }

private:
    FilmCoating coating_;
};

class ThinFilmMaterial final : public Material {
public:
    ThinFilmMaterial(FilmCoatingSpec spec, MicrofacetDistribution dist, bool smooth, bool transmission)
        : spec_(std::move(spec)), dist_(dist), smooth_(smooth), transmission_(transmission) {}

    const BSDF* getBSDF(const ShadingPoint& sp, SampledWavelengths& wl, Arena& arena) const override {
        if (transmission_) return arena.make<ThinFilmTransmissionBSDF>(FilmCoating(spec_, sp.tex, wl, arena));
        return arena.make<ThinFilmBSDF>(FilmCoating(spec_, sp.tex, wl, arena), dist_, smooth_);
    }

private:
    FilmCoatingSpec spec_;
    MicrofacetDistribution dist_;
    bool smooth_, transmission_;
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
    const bool transmission = p.getBool("transmission", false);
    if (transmission) {
        const SourceLocation loc = p.locationOf("transmission");
        if (substrate != "dielectric") failAt(loc, "transmission needs substrate = 'dielectric'");
        if (!smooth) failAt(loc, "transmission is implemented for a smooth interface only (alpha = 0)");
        const float eta0 = spec.substrateEta.at(kLambdaMin);
        for (float l = kLambdaMin; l <= kLambdaMax; l += 5.0f) {
            if (spec.substrateK.at(l) != 0) failAt(loc, "transmission needs a non-absorbing substrate (substrate_k = 0)");
            if (spec.substrateEta.at(l) != eta0)
                failAt(loc, "transmission needs a non-dispersive substrate_eta (directions would depend on λ)");
        }
        if (spec.rgbMode == FilmRGBMode::BelcourBarla)
            failAt(loc, "transmission is not available with rgb_mode 'belcour_barla'");
    }
    return std::make_shared<ThinFilmMaterial>(std::move(spec), MicrofacetDistribution(type, au, av, visible), smooth,
                                              transmission);
}

}  // namespace

IRIS_REGISTER(MaterialRegistry, "thinfilm", createThinFilm);

}  // namespace iris
