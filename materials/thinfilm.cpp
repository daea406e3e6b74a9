// Thin-film interference on a smooth or rough interface (plugin "thinfilm"): a microfacet
// reflection lobe whose Fresnel term is the exact reflectance of a film stack (film + optional
// extra layers) over a conductor or dielectric substrate, at each path wavelength and at the
// microfacet angle (materials/thin_film_coating.h):
//   rough:  f(wo, wi) = R_stack(λ, wo·h) D(h) G(wi, wo, h) / (4 cosθo cosθi)   (Walter et al. 2007
//           eq. 20 with F replaced by the stack reflectance; thesis 000 eq. 2.6),
//   smooth: delta reflection with coefficient R_stack(λ, cosθo).
// Default: reflection only, one-sided (zero for wo.z <= 0); for a dielectric substrate the
// transmitted energy is absorbed (an opaque coated surface; docs/thin_film.md).
// `transmission` = true (non-absorbing, non-dispersive dielectric substrate only): a two-sided
// interface between the exterior and the substrate medium, lit from either side (from below: the
// reversed stack). Smooth: delta reflection R and delta refraction T of the stack, the refracted
// direction by Snell's law between ext_ior and substrate_eta (the film's parallel layers do not
// change it), radiance transport scales the refracted lobe by 1/η² (pbrt-v4 ch. 9, non-symmetric scattering with refraction);
// substrate_eta = ext_ior gives a free-standing film (soap bubble): light passes straight through.
// Rough: Walter et al. 2007 reflection + transmission with F → R_stack, 1 − F → T_stack.
#include "core/registry.h"
#include "materials/material.h"
#include "materials/microfacet.h"
#include "materials/thin_film_coating.h"
#include "materials/fresnel_mueller.h"
#include "materials/mueller_frames.h"
#include "materials/thin_film_mueller.h"

#include <limits>

namespace iris {
namespace {

class ThinFilmBSDF final : public BSDF {
public:
    ThinFilmBSDF(const ThinFilmCoatingArgs& c, const MicrofacetDistribution& dist, bool smooth)
        : coating_(c.spec, c.tex, c.wl, c.arena), dist_(dist), smooth_(smooth) {}

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
        const auto r = sampleMicrofacetReflection(dist_, wo, u);
        if (!r) return std::nullopt;
        s.wi = r->wi;
        s.pdf = r->pdf();
        if (!(s.pdf > 0)) return std::nullopt;
        s.f = coating_.reflectance(r->wom) * (r->DG / (4.0f * wo.z * s.wi.z));
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

    /// Polarized: the stack's reflection matrix at the microfacet angle (materials/thin_film_mueller.h).
    MuellerSpectrum evalMueller(const vec3& wo, const vec3& wi, TransportMode) const override {
        const int n = coating_.size();
        if (smooth_ || wo.z <= 0 || wi.z <= 0) return MuellerSpectrum::depolarizer(SampledSpectrum(n));
        vec3 h = wo + wi;
        if (glm::dot(h, h) == 0) return MuellerSpectrum::depolarizer(SampledSpectrum(n));
        h = glm::normalize(h);
        const float woh = glm::dot(wo, h);
        const float DG = woh > 0 ? dist_.D(h) * dist_.G(wi, wo, h) : 0.0f;
        if (!(DG > 0)) return MuellerSpectrum::depolarizer(SampledSpectrum(n));
        return coatingReflectionMueller(coating_, woh, false, h, wi, wo) * (DG / (4.0f * wo.z * wi.z));
    }
    std::optional<PolarizedBSDFSample> sampleMueller(const vec3& wo, float uc, const vec2& u, TransportMode mode) const override {
        const std::optional<BSDFSample> s = sample(wo, uc, u, mode);
        if (!s || !smooth_) return withEvalMueller(*this, s, wo, mode);
        return withMueller(s, coatingReflectionMueller(coating_, wo.z, false, vec3(0, 0, 1), s->wi, wo),
                           SampledSpectrum(coating_.size(), 1.0f / wo.z));
    }

private:
    ThinFilmCoating coating_;
    MicrofacetDistribution dist_;
    bool smooth_;
};

/// Smooth film on a dielectric with both reflection and transmission (see the file comment).
class ThinFilmTransmissionBSDF final : public BSDF {
public:
    explicit ThinFilmTransmissionBSDF(const ThinFilmCoatingArgs& c) : coating_(c.spec, c.tex, c.wl, c.arena) {}

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

    /// Polarized: the stack's reflection or transmission matrix for the light's own path, lit from
    /// wi's side at wi's angle (T_s, T_p are reciprocal, the phases of t_s t_p* need the direction).
    std::optional<PolarizedBSDFSample> sampleMueller(const vec3& wo, float uc, const vec2& u, TransportMode mode) const override {
        const std::optional<BSDFSample> s = sample(wo, uc, u, mode);
        if (!s) return std::nullopt;
        const vec3 n(0, 0, 1);
        const float ci = std::abs(s->wi.z);
        const bool fromBelow = s->wi.z < 0;
        if (!s->isTransmission())
            return withMueller(s, coatingReflectionMueller(coating_, ci, fromBelow, n, s->wi, wo), SampledSpectrum(coating_.size(), 1.0f / ci));
        const float radiance = mode == TransportMode::Radiance ? 1.0f / (s->eta * s->eta) : 1.0f;
        return withMueller(s, coatingTransmissionMueller(coating_, ci, fromBelow, n, s->wi, wo),
                           SampledSpectrum(coating_.size(), radiance / ci));
    }

private:
    ThinFilmCoating coating_;
};

/// Rough film on a dielectric with reflection and transmission: Walter et al. 2007 (eqs. 20–21, the
/// generalized half vector eq. 16, Jacobians eqs. 14 and 17; written with the relative index as in
/// pbrt-v4's rough dielectric, ch. 9) with F → R_stack and 1 − F → T_stack at the microfacet angle, seen from the side
/// of wo. Directions below the surface are handled by mirroring both to the upper side and swapping
/// the media (the stack is then lit from the substrate side).
class ThinFilmRoughTransmissionBSDF final : public BSDF {
public:
    ThinFilmRoughTransmissionBSDF(const ThinFilmCoatingArgs& c, const MicrofacetDistribution& dist)
        : coating_(c.spec, c.tex, c.wl, c.arena), dist_(dist) {}

    uint32_t flags() const override { return kBSDFReflection | kBSDFTransmission | kBSDFGlossy; }

    SampledSpectrum eval(const vec3& woIn, const vec3& wiIn, TransportMode mode) const override {
        const int n = coating_.size();
        if (woIn.z == 0 || wiIn.z == 0) return SampledSpectrum(n);
        const bool inside = woIn.z < 0;
        const vec3 wo = inside ? -woIn : woIn, wi = inside ? -wiIn : wiIn;
        const float etap = relativeEta(inside);  // η on wi's side (when transmitted) / η on wo's side
        vec3 h;
        float denom = 0;
        if (!halfVector(wo, wi, etap, h, denom)) return SampledSpectrum(n);
        return evalAt(wo, wi, h, denom, etap, inside, mode);
    }

    float pdf(const vec3& woIn, const vec3& wiIn, TransportMode) const override {
        if (woIn.z == 0 || wiIn.z == 0) return 0.0f;
        const bool inside = woIn.z < 0;
        const vec3 wo = inside ? -woIn : woIn, wi = inside ? -wiIn : wiIn;
        const float etap = relativeEta(inside);
        vec3 h;
        float denom = 0;
        if (!halfVector(wo, wi, etap, h, denom)) return 0.0f;
        return pdfAt(wo, wi, h, denom, inside);
    }

    std::optional<BSDFSample> sample(const vec3& woIn, float uc, const vec2& u, TransportMode mode) const override {
        if (woIn.z == 0) return std::nullopt;
        const bool inside = woIn.z < 0;
        const vec3 wo = inside ? -woIn : woIn;
        const vec3 m = dist_.sampleNormal(wo, u);
        const float wom = glm::dot(wo, m);
        if (wom <= 0) return std::nullopt;
        const float pR = reflectProbability(inside, wom);
        const float etap = relativeEta(inside);
        BSDFSample s;
        vec3 wi;
        float denom = 0;
        if (uc < pR) {
            wi = reflect(wo, m);
            if (wi.z <= 0) return std::nullopt;
            s.flags = kBSDFReflection | kBSDFGlossy;
        } else {
            const float sin2T = (1.0f - wom * wom) / (etap * etap);
            if (sin2T >= 1.0f) return std::nullopt;
            const float cT = std::sqrt(1.0f - sin2T);
            wi = -wo / etap + (wom / etap - cT) * m;  // refraction about m (Snell's law about m)
            if (wi.z >= 0 || glm::dot(wi, m) >= 0) return std::nullopt;
            denom = glm::dot(wi, m) + wom / etap;
            if (denom == 0) return std::nullopt;
            s.flags = kBSDFTransmission | kBSDFGlossy;
            s.eta = etap;
        }
        // f and pdf at the sampled normal m (not recomputed from wo and wi, which cancels in float
        // near grazing angles).
        s.pdf = pdfAt(wo, wi, m, denom, inside);
        if (!(s.pdf > 0)) return std::nullopt;
        s.f = evalAt(wo, wi, m, denom, etap, inside, mode);
        s.wi = inside ? -wi : wi;
        return s;
    }

    /// Polarized: evalAt with the stack's matrices, lit from wi's side (reflection: wo's side;
    /// refraction: the other one); from below, the mirrored frame's matrix is mapped back
    /// (materials/mueller_frames.h: v → −v reverses the handedness).
    MuellerSpectrum evalMueller(const vec3& woIn, const vec3& wiIn, TransportMode mode) const override {
        const MuellerSpectrum zero = MuellerSpectrum::depolarizer(SampledSpectrum(coating_.size()));
        if (woIn.z == 0 || wiIn.z == 0) return zero;
        const bool inside = woIn.z < 0;
        const vec3 wo = inside ? -woIn : woIn, wi = inside ? -wiIn : wiIn;
        const float etap = relativeEta(inside);
        vec3 h;
        float denom = 0;
        if (!halfVector(wo, wi, etap, h, denom)) return zero;
        const float scalar = lobeFactor(wo, wi, h, denom, etap, mode);
        if (!(scalar > 0)) return zero;
        const bool refracted = wi.z < 0;
        MuellerSpectrum M = refracted ? coatingTransmissionMueller(coating_, std::abs(glm::dot(wi, h)), !inside, h, wi, wo)
                                      : coatingReflectionMueller(coating_, glm::dot(wo, h), inside, h, wi, wo);
        M *= scalar;
        return inside ? fromNestedFrame(M, Frame(vec3(-1, 0, 0), vec3(0, -1, 0), vec3(0, 0, -1)), true, wiIn, woIn) : M;
    }
    std::optional<PolarizedBSDFSample> sampleMueller(const vec3& wo, float uc, const vec2& u, TransportMode mode) const override {
        return withEvalMueller(*this, sample(wo, uc, u, mode), wo, mode);
    }

private:
    /// f in the mirrored frame (wo.z > 0) for the microfacet normal h.
    SampledSpectrum evalAt(const vec3& wo, const vec3& wi, const vec3& h, float denom, float etap, bool inside,
                           TransportMode mode) const {
        const int n = coating_.size();
        SampledSpectrum R, T;
        stackAt(inside, glm::dot(wo, h), R, T);
        const float v = lobeFactor(wo, wi, h, denom, etap, mode);
        if (v == 0) return SampledSpectrum(n);
        return (wi.z > 0 ? R : T) * v;
    }
    /// evalAt's factor of R (reflection) or T (refraction); 0 where D G vanishes.
    float lobeFactor(const vec3& wo, const vec3& wi, const vec3& h, float denom, float etap, TransportMode mode) const {
        const float DG = dist_.D(h) * dist_.G(wi, wo, h);
        if (!(DG > 0)) return 0.0f;
        if (wi.z > 0) return DG / (4.0f * wo.z * wi.z);  // Walter eq. 20
        // Walter eq. 21 in pbrt-v4's relative-index form: T D G |wi·h wo·h| / (|cosθi cosθo| (wi·h + wo·h/η')²), /η'² for radiance.
        float ft = DG * std::abs(glm::dot(wi, h) * glm::dot(wo, h) / (wi.z * wo.z * denom * denom));
        if (mode == TransportMode::Radiance) ft /= etap * etap;
        return ft;
    }

    /// pdf in the mirrored frame for the microfacet normal h.
    float pdfAt(const vec3& wo, const vec3& wi, const vec3& h, float denom, bool inside) const {
        const float pR = reflectProbability(inside, glm::dot(wo, h));
        const float pm = dist_.pdf(wo, h);
        if (wi.z > 0) return pR * pm / (4.0f * glm::dot(wo, h));                        // Walter eq. 14
        return (1.0f - pR) * pm * std::abs(glm::dot(wi, h)) / (denom * denom);          // Walter eq. 17
    }

    /// η on the far side / η on wo's side.
    float relativeEta(bool inside) const {
        const float r = float(coating_.substrateIor(0).real() / coating_.extIor());
        return inside ? 1.0f / r : r;
    }
    /// Half vector (reflection) or generalized half vector h ∝ η' wi + wo (transmission), h.z > 0;
    /// false for degenerate or back-facing configurations (as pbrt-v4's rough dielectric does).
    static bool halfVector(const vec3& wo, const vec3& wi, float etap, vec3& h, float& denom) {
        const bool reflect = wi.z > 0;
        h = reflect ? wo + wi : wi * etap + wo;
        if (glm::dot(h, h) == 0) return false;
        h = glm::normalize(h);
        if (h.z < 0) h = -h;
        if (glm::dot(h, wi) * wi.z < 0 || glm::dot(h, wo) * wo.z < 0) return false;
        denom = reflect ? 0.0f : glm::dot(wi, h) + glm::dot(wo, h) / etap;
        if (!reflect && denom == 0) return false;
        return glm::dot(wo, h) > 0;
    }
    /// The stack at the microfacet angle from wo's side. sample() needs it three times at the same
    /// angle (lobe choice, pdf, f) and light sampling twice (eval, pdf): the last result is kept and
    /// reused for the same (side, cosθ) — identical values; the BSDF belongs to one path/thread.
    void stackAt(bool inside, float cosTheta, SampledSpectrum& R, SampledSpectrum& T) const {
        if (!(cosTheta == cacheCos_ && inside == cacheInside_)) {
            if (inside) coating_.fromBelowRT(cosTheta, cacheR_, cacheT_);
            else coating_.reflectanceTransmittance(cosTheta, cacheR_, cacheT_);
            cacheCos_ = cosTheta;
            cacheInside_ = inside;
        }
        R = cacheR_;
        T = cacheT_;
    }
    float reflectProbability(bool inside, float cosTheta) const {
        SampledSpectrum R, T;
        stackAt(inside, cosTheta, R, T);
        const float r = R.average(), t = T.average();
        return r + t > 0 ? r / (r + t) : 1.0f;
    }

    ThinFilmCoating coating_;
    MicrofacetDistribution dist_;
    mutable float cacheCos_ = std::numeric_limits<float>::quiet_NaN();
    mutable bool cacheInside_ = false;
    mutable SampledSpectrum cacheR_, cacheT_;
};

class ThinFilmMaterial final : public Material {
public:
    ThinFilmMaterial(ThinFilmCoatingSpec spec, MicrofacetDistribution dist, bool smooth, bool transmission)
        : spec_(std::move(spec)), dist_(dist), smooth_(smooth), transmission_(transmission) {}

    const BSDF* getBSDF(const ShadingPoint& sp, SampledWavelengths& wl, Arena& arena) const override {
        // The coating is built in place inside the BSDF (no copy of its per-wavelength arrays).
        const ThinFilmCoatingArgs c{spec_, sp.tex, wl, arena};
        if (transmission_ && smooth_) return arena.make<ThinFilmTransmissionBSDF>(c);
        if (transmission_) return arena.make<ThinFilmRoughTransmissionBSDF>(c, dist_);
        return arena.make<ThinFilmBSDF>(c, dist_, smooth_);
    }

private:
    ThinFilmCoatingSpec spec_;
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
    ThinFilmCoatingSpec spec = ThinFilmCoatingSpec::fromProperties(p, defEta, defK);
    // The truncated sum loops over `bounces` per evaluation: an absurd count would hang the render.
    if (spec.bounces > 1000) failAt(p.locationOf("bounces"), "thinfilm: bounces must be in [0, 1000], got ", spec.bounces);
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
        const float eta0 = spec.substrateEta.eval(kLambdaMin);
        for (float l = kLambdaMin; l <= kLambdaMax; l += 5.0f) {
            if (spec.substrateK.eval(l) != 0) failAt(loc, "transmission needs a non-absorbing substrate (substrate_k = 0)");
            if (spec.substrateEta.eval(l) != eta0)
                failAt(loc, "transmission needs a non-dispersive substrate_eta (directions would depend on λ)");
        }
        if (spec.rgbMode != ThinFilmRGBMode::Point)
            failAt(loc, "transmission is not available with rgb_mode '", p.getString("rgb_mode"), "'");
    }
    return std::make_shared<ThinFilmMaterial>(std::move(spec), MicrofacetDistribution(type, au, av, visible), smooth,
                                              transmission);
}

}  // namespace

IRIS_REGISTER(MaterialRegistry, "thinfilm", createThinFilm);

}  // namespace iris
