// Granier & Heidrich 2003, "A simple layered RGB BRDF model", as formulated and implemented in
// thesis 000 §2.4 (eqs. 2.23–2.35) and §3.1 (eqs. 3.1–3.13): a thin dielectric film (top normal
// n0, possibly tilted) over a diffuse base (normal n1), with Phong lobes for the reflection at the
// film and the internal reflection, Schlick's Fresnel, and an interference (phase) term per
// channel. Not energy conserving by design (the phase term can add energy).
//
// Mitsuba plugin "granier". Parameters (see docs/thesis_models.md for the readings chosen):
//   n0           vector   top (film) normal in the local shading frame        default (0,0,1)
//   n1           vector   base normal in the local shading frame              default (0,0,1)
//   eta_i        float|preset name  index of the outside medium               default 1.0
//   eta_t        any IOR form  film index per channel (materials/thesis/thesis_channels.h)  default (1.5,1.6,1.8)
//   thickness    float|texture film thickness d in nm                         default 76
//   wavelengths  rgb      λ of each channel in nm                   default defaultChannelWavelengths()
//   e0, e1       float    Phong exponents of the outer / inner reflection     default 130, 130
//   ws, wd       spectrum|texture weights of the dielectric / diffuse part    default 0.5, 0.5
//
// Direction mapping: the thesis' incident ωi is our wi (towards the light), its outgoing ωo is
// our wo (towards the viewer).
#include "core/registry.h"
#include "core/sampling.h"
#include "materials/fresnel.h"
#include "materials/material.h"
#include "materials/textures/texture_params.h"
#include "materials/thesis/thesis_channels.h"

namespace iris {
namespace {

/// Refraction of w (pointing away from the film, w·n > 0) into the film through the interface
/// with unit normal n; eta = η_i/η_t. Returns false under total internal reflection.
/// t = −eta w + (eta (w·n) − cosθt) n, cosθt = sqrt(1 − eta² (1 − (w·n)²))  (thesis eqs. 3.1–3.2,
/// read as Snell's law about n0; see docs/thesis_models.md).
bool refractInto(const vec3& w, const vec3& n, float eta, vec3* t, float* cosT) {
    const float c = glm::dot(w, n);
    const float s2 = eta * eta * (1.0f - c * c);
    if (s2 >= 1.0f) return false;
    *cosT = std::sqrt(1.0f - s2);
    *t = -eta * w + (eta * c - *cosT) * n;
    return true;
}

/// Phong lobe cos^e for cos > 0, zero otherwise (also for e = 0, where pow(0, 0) would be 1).
inline float phongLobe(float cosine, float e) { return cosine > 0 ? std::pow(cosine, e) : 0.0f; }

class GranierBSDF final : public BSDF {
public:
    struct Params {
        vec3 n0, n1;
        float etaI, e0, e1, d;
        SampledSpectrum etaT, lambda, ws, wd;
    };
    explicit GranierBSDF(const Params& p) : p_(p) {}

    SampledSpectrum eval(const vec3& wo, const vec3& wi, TransportMode mode) const override {
        // The model is not reciprocal (Fresnel factors of eqs. 2.23, 2.27 use the light side):
        // importance transport uses the adjoint f*(wo, wi) = f(wi, wo).
        return mode == TransportMode::Importance ? evalRadiance(wi, wo) : evalRadiance(wo, wi);
    }

    SampledSpectrum evalRadiance(const vec3& wo, const vec3& wi) const {
        const int n = p_.etaT.size();
        SampledSpectrum f(n);
        if (wo.z <= 0 || wi.z <= 0) return f;
        const float cosI = glm::dot(wi, p_.n0), cosO = glm::dot(wo, p_.n0);
        const bool film = cosI > 0 && cosO > 0;  // both directions see the top interface
        const vec3 wri = reflect(wi, p_.n0);     // ωri = 2(ωi·n0)n0 − ωi   (eq. 3.3)
        const float lobeR = phongLobe(glm::dot(wri, wo), p_.e0);
        for (int c = 0; c < n; ++c) {
            const float etaT = p_.etaT[c], lambda = p_.lambda[c];
            float fs = 0.0f;
            if (film) {
                const float f0 = sqr((p_.etaI - etaT) / (p_.etaI + etaT));  // eq. 2.25
                const float Fi = fresnelSchlick(cosI, f0);                   // eq. 2.24
                const float fr = Fi * lobeR;                                  // eq. 2.23
                float ft = 0.0f, phase = 0.0f;
                vec3 wti, wto;
                float cosTi, cosTo;
                const float eta = p_.etaI / etaT;
                if (refractInto(wi, p_.n0, eta, &wti, &cosTi) && refractInto(wo, p_.n0, eta, &wto, &cosTo)) {
                    const vec3 wrti = wti - 2.0f * glm::dot(wti, p_.n1) * p_.n1;  // eq. 3.4 (base mirror)
                    const float lobeT = phongLobe(glm::dot(wrti, -wto), p_.e1);
                    const float Fto = fresnelSchlick(cosTo, f0);
                    ft = (1.0f - Fi) * lobeT * (1.0f - Fto);  // eq. 2.27
                    // Φ = π η_t d/λ ((ωti + ωto)·(−n0))   (eq. 2.28)
                    phase = kPi * etaT * p_.d / lambda * glm::dot(wti + wto, -p_.n0);
                }
                const float fphi = 2.0f * std::cos(2.0f * phase) * std::sqrt(fr * ft);  // eq. 2.29
                fs = fr + ft + fphi;                                                     // eq. 2.30
            }
            // Diffuse part (eqs. 2.32, 2.34): Td = 80/21 η_i η_t/(η_t+η_i)²,
            // fd = 1 + 2 cos(4π η_t d/λ) sqrt(Td (1 − Td)); fd is read as the base albedo (÷π).
            const float Td = 80.0f / 21.0f * p_.etaI * etaT / sqr(etaT + p_.etaI);
            const float fd = 1.0f + 2.0f * std::cos(4.0f * kPi * etaT * p_.d / lambda) * std::sqrt(Td * (1.0f - Td));
            f[c] = p_.ws[c] * fs + p_.wd[c] * fd * kInvPi;  // eq. 2.35
        }
        return f;
    }

    /// Probability of sampling the Phong lobe: the reflected energy at the top interface
    /// (Schlick F at wo about n0, averaged over the path's channels) — eq. 3.12.
    float lobeProbability(const vec3& wo) const {
        const float c = glm::dot(wo, p_.n0);
        if (c <= 0) return 0.0f;
        float s = 0.0f;
        const int n = p_.etaT.size();
        for (int k = 0; k < n; ++k) s += fresnelSchlick(c, sqr((p_.etaI - p_.etaT[k]) / (p_.etaI + p_.etaT[k])));
        return std::clamp(s / float(n), 0.0f, 1.0f);
    }

    std::optional<BSDFSample> sample(const vec3& wo, float uc, const vec2& u, TransportMode mode) const override {
        if (wo.z <= 0) return std::nullopt;
        const float ps = lobeProbability(wo);
        vec3 wi;
        if (uc < ps) {
            // Phong lobe around the mirror direction of wo about n0 (eqs. 3.5–3.6).
            const float cosS = std::pow(1.0f - u.y, 1.0f / (p_.e0 + 1.0f));
            const float sinS = safeSqrt(1.0f - cosS * cosS);
            const float phi = 2.0f * kPi * u.x;
            wi = Frame::fromNormal(reflect(wo, p_.n0)).toWorld(vec3(sinS * std::cos(phi), sinS * std::sin(phi), cosS));
        } else {
            wi = Frame::fromNormal(p_.n1).toWorld(sampleCosineHemisphere(u));  // eqs. 3.8–3.10
        }
        if (wi.z <= 0) return std::nullopt;
        BSDFSample s;
        s.wi = glm::normalize(wi);
        s.pdf = pdf(wo, s.wi, mode);
        if (!(s.pdf > 0)) return std::nullopt;
        s.f = eval(wo, s.wi, mode);
        s.flags = kBSDFReflection | (uc < ps ? kBSDFGlossy : kBSDFDiffuse);
        return s;
    }

    /// Mixture density of the two strategies (eq. 3.13 read with the selection probabilities of
    /// eq. 3.12): P·(e0+1)/(2π)·(ωri·wi)^e0 + (1−P)·(wi·n1)/π  (eqs. 3.7, 3.11).
    float pdf(const vec3& wo, const vec3& wi, TransportMode) const override {
        if (wo.z <= 0 || wi.z <= 0) return 0.0f;
        const float ps = lobeProbability(wo);
        float p = 0.0f;
        if (ps > 0) {
            p += ps * (p_.e0 + 1.0f) * kInv2Pi * phongLobe(glm::dot(reflect(wo, p_.n0), wi), p_.e0);
        }
        p += (1.0f - ps) * std::max(0.0f, glm::dot(wi, p_.n1)) * kInvPi;
        return p;
    }

    uint32_t flags() const override { return kBSDFReflection | kBSDFGlossy | kBSDFDiffuse; }

private:
    Params p_;
};

class GranierMaterial final : public Material {
public:
    explicit GranierMaterial(const Properties& p) {
        n0_ = p.getVector("n0", vec3(0, 0, 1));
        n1_ = p.getVector("n1", vec3(0, 0, 1));
        if (!(glm::length(n0_) > 0) || !(glm::length(n1_) > 0))
            failAt(p.location(), "granier: n0 and n1 must be non-zero vectors");
        n0_ = glm::normalize(n0_);
        n1_ = glm::normalize(n1_);
        if (n0_.z <= 0 || n1_.z <= 0) failAt(p.location(), "granier: n0 and n1 must point into the upper hemisphere (z > 0)");
        etaI_ = readConstantIOR(p, "eta_i", 1.0f);
        channels_ = ThesisChannels::read(p, "granier", vec3(1.5f, 1.6f, 1.8f));
        thickness_ = getFloatTexture(p, "thickness", 76.0f);
        if (thickness_->isConstant() && !(thickness_->eval({}) >= 0))
            failAt(p.locationOf("thickness"), "granier: thickness must be >= 0 nm, got ", thickness_->eval({}));
        e0_ = p.getFloat("e0", 130.0f);
        e1_ = p.getFloat("e1", 130.0f);
        if (!(e0_ >= 0) || !(e1_ >= 0)) failAt(p.location(), "granier: Phong exponents e0, e1 must be >= 0");
        ws_ = getSpectrumTexture(p, "ws", SpectrumKind::Reflectance, 0.5f);
        wd_ = getSpectrumTexture(p, "wd", SpectrumKind::Reflectance, 0.5f);
    }

    const BSDF* getBSDF(const ShadingPoint& sp, SampledWavelengths& wl, Arena& arena) const override {
        GranierBSDF::Params q;
        q.n0 = n0_;
        q.n1 = n1_;
        q.etaI = etaI_;
        q.e0 = e0_;
        q.e1 = e1_;
        q.d = std::max(0.0f, thickness_->eval(sp.tex));
        q.etaT = channels_.etaT.sample(channels_.of(wl));
        q.lambda = channels_.lambdasOf(wl);
        q.ws = ws_->eval(sp.tex, wl);
        q.wd = wd_->eval(sp.tex, wl);
        return arena.make<GranierBSDF>(q);
    }

private:
    vec3 n0_, n1_;
    float etaI_, e0_, e1_;
    ThesisChannels channels_;
    FloatTexturePtr thickness_;
    SpectrumTexturePtr ws_, wd_;
};

std::shared_ptr<Material> createGranier(const Properties& p) { return std::make_shared<GranierMaterial>(p); }

}  // namespace

IRIS_REGISTER(MaterialRegistry, "granier", createGranier);

}  // namespace iris
