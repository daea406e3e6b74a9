#include "materials/gltf_pbr_bsdf.h"

#include <algorithm>

#include "core/sampling.h"
#include "materials/gltf_pbr_terms.h"
#include "materials/thin_film_gltf.h"

namespace iris::gltf {

namespace {

constexpr uint32_t kNullLobe = kBSDFNull | kBSDFTransmission | kBSDFSpecular;

float max3(const vec3& v) { return std::max(v.x, std::max(v.y, v.z)); }

/// The lane-wise Schlick f0 + (1 − f0) w.
SampledSpectrum schlick(const SampledSpectrum& f0, float w) { return f0 + (SampledSpectrum(f0.size(), 1.0f) - f0) * w; }

/// A direction below the surface mirrored above it (the thin-walled BTDF's reflection partner).
vec3 mirrored(const vec3& w) { return vec3(w.x, w.y, -w.z); }

/// The refraction pair (wo above, wi below) of a volume boundary at its generalised half vector
/// h ∝ wo + eta·wi, turned to +z (Walter et al. 2007 eq. 16; the README's H_TR = −normalize(η_i V +
/// η_o L)), eta = η beyond the surface / η on the viewer's side.
struct Refraction {
    vec3 h;
    float dotO, dotI;
};
std::optional<Refraction> refractionHalf(const vec3& wo, const vec3& wi, float eta) {
    vec3 h = wo + wi * eta;
    const float len = glm::length(h);
    if (!(len > 0)) return std::nullopt;
    h /= len;
    if (h.z < 0) h = -h;
    const Refraction r{h, glm::dot(wo, h), glm::dot(wi, h)};
    // Each direction must see the front of the microfacet on its own side.
    if (!(r.dotO > 0 && r.dotI < 0 && h.z > 0)) return std::nullopt;
    return r;
}

float sqr(float x) { return x * x; }

}  // namespace

PbrBSDF::PbrBSDF(const PbrPoint& p)
    : p_(p),
      spec_(MicrofacetType::GGX, p.alpha, p.alpha, true, ShadowingModel::SmithSeparable),
      coat_(MicrofacetType::GGX, p.coatAlpha, p.coatAlpha, true, ShadowingModel::SmithSeparable) {
    // Lobe probabilities: rough estimates of each lobe's share of the reflected energy (any
    // positive choice is unbiased; pdf() uses the same mixture).
    const float lum = (p.baseRGB.x + p.baseRGB.y + p.baseRGB.z) / 3.0f;
    const float dielectric = 1.0f - p.metallic;
    lobeProb_[kDiffuse] = dielectric * (1.0f - p.transmission) * lum;
    lobeProb_[kSpecular] = p.metallic + dielectric * std::max(0.25f, p.iridescence * 0.5f);
    lobeProb_[kTransmission] = dielectric * p.transmission * std::max(lum, 0.05f);
    lobeProb_[kSheen] = 0.5f * p.sheenMax;
    lobeProb_[kCoat] = 0.25f * p.clearcoat;
    float sum = 0;
    for (float w : lobeProb_) sum += w;
    for (float& w : lobeProb_) w = sum > 0 ? w / sum : 0.0f;
    if (!(sum > 0)) lobeProb_[kSpecular] = 1.0f;
}

uint32_t PbrBSDF::flags() const {
    uint32_t f = kBSDFReflection | kBSDFGlossy | kBSDFDiffuse;
    if (p_.transmission > 0 && p_.metallic < 1) f |= kBSDFTransmission;
    if (p_.opacity < 1 || !mirrorsBack()) f |= kNullLobe;
    return f;
}

SampledSpectrum PbrBSDF::metalFresnel(float vh) const {
    SampledSpectrum F = schlick(p_.base, schlickWeight(vh));  // B.3.4 with f0 = baseColor
    // Cycles 4.2 puts no film on metals (commit 17f2cdd1: dielectric bases only), so its reading
    // leaves the metal's Fresnel term as it is.
    const bool noFilm = p_.rgb && p_.mode == ThinFilmRGBMode::Cycles42;
    if (p_.iridescence > 0 && !noFilm) F = F * (1.0f - p_.iridescence) + thinFilmFresnel(p_, vh, true) * p_.iridescence;
    return F;
}

SampledSpectrum PbrBSDF::dielectricFresnel(float vh, float w, SampledSpectrum& baseWeight) const {
    const int n = p_.base.size();
    if (w < 0) {
        // KHR_materials_volume, total internal reflection: F = 1, its F90 not scaled by
        // KHR_materials_specular (README "Interaction with other extensions"); nothing enters the base.
        baseWeight = SampledSpectrum(n);
        return SampledSpectrum(n, 1.0f);
    }
    const float f0 = (p_.ior - 1.0f) / (p_.ior + 1.0f) * ((p_.ior - 1.0f) / (p_.ior + 1.0f));
    SampledSpectrum f0c = p_.specularColor * f0;
    for (int i = 0; i < n; ++i) f0c[i] = std::min(f0c[i], 1.0f);
    const vec3 f0rgb = glm::min(p_.specularColorRGB * f0, vec3(1.0f));
    const float frMax = max3(f0rgb + (vec3(1.0f) - f0rgb) * w);  // KHR_materials_specular: max_value(fr)
    SampledSpectrum F = schlick(f0c, w) * p_.specular;
    if (p_.iridescence <= 0) {
        baseWeight = SampledSpectrum(n, 1.0f - p_.specular * frMax);
        return F;
    }
    const SampledSpectrum film = thinFilmFresnel(p_, vh, false);
    F = F * (1.0f - p_.iridescence) + film * p_.iridescence;
    if (p_.rgb && p_.mode == ThinFilmRGBMode::Khr) {
        baseWeight = SampledSpectrum(n, 1.0f - F.maxValue());  // README rgb_mix: 1 − max₃
    } else {
        // Exact reading: what the film does not reflect at this lane enters the base.
        baseWeight = SampledSpectrum(n, 1.0f) - (SampledSpectrum(n, p_.specular * frMax) * (1.0f - p_.iridescence) + film * p_.iridescence);
    }
    return F;
}

SampledSpectrum PbrBSDF::surface(const vec3& wo, const vec3& wi, float eta, TransportMode mode) const {
    const int n = p_.base.size();
    const bool transmit = wi.z < 0;
    if (transmit && !(p_.transmission > 0 && p_.metallic < 1)) return SampledSpectrum(n);
    SampledSpectrum f(n);
    float vh;  // |v·h| of the clearcoat's Fresnel
    if (transmit && p_.volume) {
        const std::optional<Refraction> r = refractionHalf(wo, wi, eta);
        if (!r) return f;
        const float w = volumeSchlickWeight(r->dotO, eta);
        if (w < 0) return f;  // total internal reflection: nothing is transmitted
        SampledSpectrum baseWeight(n);
        dielectricFresnel(r->dotO, w, baseWeight);
        // KHR_materials_volume "Implementation", Walter et al. 2007 eq. 21 with η_o (viewer) = 1,
        // η_i = eta: |h·l||h·v| / (|n·l||n·v|) · G D / ((v·h) + eta (l·h))², G = 4 V |n·l||n·v|.
        float btdf = 4.0f * ggxV(spec_.alphaX(), wi.z, wo.z) * ggxD(spec_.alphaX(), r->h) * std::abs(r->dotO * r->dotI) /
                     sqr(r->dotO + eta * r->dotI);
        if (mode == TransportMode::Importance) btdf *= eta * eta;  // the adjoint: η_i² for η_o²
        f = baseWeight * p_.base * (p_.transmission * btdf * (1.0f - p_.metallic));
        vh = r->dotO;
    } else {
        const vec3 l = transmit ? mirrored(wi) : wi;
        const vec3 h = glm::normalize(l + wo);
        vh = std::abs(glm::dot(wo, h));
        const float spec = specularBrdf(spec_.alphaX(), l, wo);
        // A volume boundary's reflection takes the Fresnel of the dense side (README cases 1–3).
        const float w = p_.volume ? volumeSchlickWeight(vh, eta) : schlickWeight(vh);
        SampledSpectrum baseWeight(n);
        const SampledSpectrum Fd = dielectricFresnel(vh, w, baseWeight);
        if (!transmit) {
            const SampledSpectrum diffuse = p_.base * ((1.0f - p_.transmission) * kInvPi);
            f = (baseWeight * diffuse + Fd * spec) * (1.0f - p_.metallic);
            if (p_.metallic > 0) f += metalFresnel(vh) * (spec * p_.metallic);
        } else {
            f = baseWeight * p_.base * (p_.transmission * spec * (1.0f - p_.metallic));  // thin-walled specular_btdf
        }
    }
    if (p_.sheenMax > 0) {
        // KHR_materials_sheen's albedo scaling, clamped at 0: E exceeds 1 at grazing angles of the
        // smoothest sheens, where the unclamped formula would make the base negative.
        const float scale = std::max(0.0f, std::min(1.0f - p_.sheenMax * sheenAlbedo(wo.z, p_.sheenRoughness),
                                                    1.0f - p_.sheenMax * sheenAlbedo(std::abs(wi.z), p_.sheenRoughness)));
        f = f * scale;
        if (!transmit) f += p_.sheenColor * sheenBrdf(p_.sheenAlpha, wi, wo);
    }
    if (p_.clearcoat > 0) {
        const float Fc = 0.04f + 0.96f * schlickWeight(vh);
        f = f * (1.0f - p_.clearcoat * Fc);
        if (!transmit) f += SampledSpectrum(n, p_.clearcoat * Fc * specularBrdf(coat_.alphaX(), wi, wo));
    }
    return f;
}

SampledSpectrum PbrBSDF::evalFront(const vec3& wo, const vec3& wi, float eta, TransportMode mode) const {
    if (wo.z <= 0 || wi.z == 0) return SampledSpectrum(p_.base.size());
    return surface(wo, wi, eta, mode) * p_.opacity;
}

SampledSpectrum PbrBSDF::eval(const vec3& wo, const vec3& wi, TransportMode mode) const {
    if (wo.z < 0 && mirrorsBack()) return evalFront(-wo, -wi, backEta(), mode);  // mirrored: −w has the same angle to −n
    return evalFront(wo, wi, p_.ior, mode);
}

float PbrBSDF::surfacePdf(const vec3& wo, const vec3& wi, float eta) const {
    const bool transmit = wi.z < 0;
    if (transmit && p_.volume) {
        const std::optional<Refraction> r = refractionHalf(wo, wi, eta);
        if (!r) return 0.0f;
        // Walter et al. 2007 eq. 17: |∂ω_h/∂ω_i| = eta² |l·h| / ((v·h) + eta (l·h))².
        return lobeProb_[kTransmission] * spec_.pdf(wo, r->h) * eta * eta * std::abs(r->dotI) / sqr(r->dotO + eta * r->dotI);
    }
    const vec3 l = transmit ? mirrored(wi) : wi;
    const vec3 h = glm::normalize(l + wo);
    const float jac = 1.0f / (4.0f * std::abs(glm::dot(wo, h)));
    if (transmit) return lobeProb_[kTransmission] * spec_.pdf(wo, h) * jac;
    return (lobeProb_[kDiffuse] + lobeProb_[kSheen]) * cosineHemispherePdf(wi.z) + lobeProb_[kSpecular] * spec_.pdf(wo, h) * jac +
           lobeProb_[kCoat] * coat_.pdf(wo, h) * jac;
}

float PbrBSDF::pdfFront(const vec3& wo, const vec3& wi, float eta) const {
    if (wo.z <= 0 || wi.z == 0) return 0.0f;
    return p_.opacity * surfacePdf(wo, wi, eta);
}

float PbrBSDF::pdf(const vec3& wo, const vec3& wi, TransportMode) const {
    if (wo.z < 0 && mirrorsBack()) return pdfFront(-wo, -wi, backEta());
    return pdfFront(wo, wi, p_.ior);
}

std::optional<BSDFSample> PbrBSDF::passThrough(const vec3& wo, float weight, float prob) const {
    BSDFSample s;
    s.wi = -wo;
    s.pdf = prob;
    s.f = SampledSpectrum(p_.base.size(), weight / std::abs(wo.z));  // f·|cosθi|/pdf = weight/prob
    s.flags = kNullLobe;
    return s;
}

std::optional<BSDFSample> PbrBSDF::sample(const vec3& wo, float uc, const vec2& u, TransportMode mode) const {
    if (wo.z == 0) return std::nullopt;
    if (wo.z < 0 && !mirrorsBack()) return passThrough(wo, 1.0f, 1.0f);  // culled back face
    if (wo.z > 0) return sampleFront(wo, uc, u, p_.ior, mode);
    std::optional<BSDFSample> s = sampleFront(-wo, uc, u, backEta(), mode);
    if (s) s->wi = -s->wi;
    return s;
}

std::optional<BSDFSample> PbrBSDF::sampleFront(const vec3& wo, float uc, const vec2& u, float eta, TransportMode mode) const {
    if (uc >= p_.opacity) return passThrough(wo, 1.0f - p_.opacity, 1.0f - p_.opacity);  // alpha coverage
    uc /= p_.opacity;
    int lobe = 0;
    for (float acc = lobeProb_[0]; lobe < kLobes - 1 && uc >= acc; acc += lobeProb_[++lobe]) {}
    vec3 wi;
    uint32_t flags = kBSDFReflection | kBSDFGlossy;
    switch (lobe) {
        case kDiffuse:
        case kSheen: wi = sampleCosineHemisphere(u), flags = kBSDFReflection | kBSDFDiffuse; break;
        case kSpecular: wi = reflect(wo, spec_.sampleNormal(wo, u)); break;
        case kTransmission:
            flags = kBSDFTransmission | kBSDFGlossy;
            if (p_.volume) {
                // Snell's law at the sampled microfacet h (Walter et al. 2007 eq. 40):
                // wi = −wo/eta + ((wo·h)/eta − cosθt) h, sin²θt = (1 − (wo·h)²)/eta².
                const vec3 h = spec_.sampleNormal(wo, u);
                const float c = glm::dot(wo, h);
                const float sin2t = (1.0f - c * c) / (eta * eta);
                if (!(c > 0) || sin2t >= 1.0f) return std::nullopt;  // back-facing microfacet, or total internal reflection
                wi = glm::normalize(-wo / eta + h * (c / eta - std::sqrt(1.0f - sin2t)));
            } else {
                wi = mirrored(reflect(wo, spec_.sampleNormal(wo, u)));
            }
            break;
        default: wi = reflect(wo, coat_.sampleNormal(wo, u)); break;
    }
    if ((lobe == kTransmission) != (wi.z < 0) || wi.z == 0) return std::nullopt;
    // The front side's pdf and value (for the back side, wo is already mirrored and eta inverted).
    BSDFSample s;
    s.wi = wi;
    s.pdf = pdfFront(wo, wi, eta);
    if (!(s.pdf > 0)) return std::nullopt;
    s.f = evalFront(wo, wi, eta, mode);
    s.flags = flags;
    if (lobe == kTransmission && p_.volume) s.eta = eta;
    return s;
}

}  // namespace iris::gltf
