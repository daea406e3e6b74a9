// Fresnel reflectance: exact unpolarised dielectric (both sides, total internal reflection),
// exact conductor with a complex index of refraction, and Schlick's approximation.
// Per-float functions plus SampledSpectrum overloads (one value per wavelength).
//
// Conventions (as Mitsuba 3 / pbrt-v4 §9.3): cosThetaI is the cosine of the incident direction
// with the normal of the interface, positive on the outside (the side with η_ext); eta is the
// relative index η_int / η_ext. A negative cosThetaI means the light arrives from the inside, so
// the relative index crossed is 1/eta.
#pragma once

#include <complex>

#include "core/frame.h"
#include "core/math.h"
#include "spectral/sampled_spectrum.h"

namespace iris {

/// Everything a smooth or rough dielectric needs from one Fresnel evaluation.
struct FresnelDielectricResult {
    float R = 1.0f;          // unpolarised reflectance (1 under total internal reflection)
    float cosThetaT = 0.0f;  // cosine of the refracted direction, sign opposite to cosThetaI
    float etaIT = 1.0f;      // η_t / η_i for this side (eta, or 1/eta from the inside)
    float etaTI = 1.0f;      // η_i / η_t = 1 / etaIT
};

/// Exact unpolarised dielectric Fresnel (pbrt-v4 §9.3 eqs. 9.4–9.5; Snell's law for cosθt):
///   r⊥ = (cosθi − η cosθt)/(cosθi + η cosθt), r∥ = (η cosθi − cosθt)/(η cosθi + cosθt),
///   R = (r⊥² + r∥²)/2, with η = η_t/η_i for the side the light arrives on.
/// Equivalent to thesis 000 eqs. 2.8–2.9 (Walter et al. 2007 eq. 22); see fresnelDielectricWalter.
inline FresnelDielectricResult fresnelDielectricFull(float cosThetaI, float eta) {
    FresnelDielectricResult r;
    const bool outside = cosThetaI >= 0.0f;
    r.etaIT = outside ? eta : 1.0f / eta;
    r.etaTI = outside ? 1.0f / eta : eta;
    if (eta == 1.0f) {  // index-matched: everything passes straight through
        r.R = 0.0f;
        r.cosThetaT = -cosThetaI;
        return r;
    }
    const float ci = std::min(1.0f, std::abs(cosThetaI));
    // Snell: sin²θt = sin²θi · (η_i/η_t)².
    const float sin2T = (1.0f - ci * ci) * r.etaTI * r.etaTI;
    if (sin2T >= 1.0f) {  // total internal reflection
        r.R = 1.0f;
        r.cosThetaT = 0.0f;
        return r;
    }
    const float ct = std::sqrt(1.0f - sin2T);
    const float rPerp = (ci - r.etaIT * ct) / (ci + r.etaIT * ct);
    const float rPar = (r.etaIT * ci - ct) / (r.etaIT * ci + ct);
    r.R = std::min(1.0f, 0.5f * (rPerp * rPerp + rPar * rPar));
    r.cosThetaT = outside ? -ct : ct;
    return r;
}

/// Reflectance only (see fresnelDielectricFull).
inline float fresnelDielectric(float cosThetaI, float eta) { return fresnelDielectricFull(cosThetaI, eta).R; }

/// The per-channel Fresnel reflectance in the adjoint of a refraction whose direction one index
/// etaDir decided (wo's side at cosO, wi's at cosI, both against the same normal): a channel of
/// that index keeps its value from wo's side (equal to wi's, and to what the lobe choice used); a
/// channel of another index takes it from wi's side, as the radiance BSDF of the reverse direction
/// does (importance transport f*(wo, wi) = f(wi, wo), Veach 1997 eq. 3.21).
template <typename Spectrum>
Spectrum fresnelDielectricAdjoint(float cosO, float cosI, const Spectrum& eta, float etaDir) {
    Spectrum F(eta.size());
    for (int k = 0; k < eta.size(); ++k) F[k] = fresnelDielectric(eta[k] == etaDir ? cosO : cosI, eta[k]);
    return F;
}

/// The thesis' form, thesis 000 eqs. 2.8–2.9 (Walter et al. 2007 eq. 22, Cook & Torrance 1982):
///   F = ½ (g−c)²/(g+c)² · (1 + (c(g+c)−1)²/(c(g−c)−1)²), g = sqrt(η_t²/η_i² − 1 + c²), c = |cosθi|.
/// Only for incidence from the outside with relative index eta; g imaginary means TIR (F = 1).
inline float fresnelDielectricWalter(float c, float eta) {
    c = std::abs(c);
    const float g2 = eta * eta - 1.0f + c * c;
    if (g2 < 0.0f) return 1.0f;
    const float g = std::sqrt(g2);
    const float a = (g - c) / (g + c);
    const float b = (c * (g + c) - 1.0f) / (c * (g - c) + 1.0f);
    // Walter 2007 eq. 22 denominator is c(g−c)+1; the thesis prints "−1" (typo: at c = 1 it would
    // not reduce to ((η−1)/(η+1))²).
    return 0.5f * a * a * (1.0f + b * b);
}

/// Exact conductor Fresnel for complex relative index η + iκ (pbrt-v4 §9.3.6, eqs. 9.4–9.5 with
/// complex η): cosθt = sqrt(1 − sin²θi/η²) (complex), same r⊥, r∥ as the dielectric, R = (|r⊥|² + |r∥|²)/2.
/// eta, k are relative to the outside medium. Incidence from the outside only (cosThetaI clamped).
inline float fresnelConductor(float cosThetaI, float eta, float k) {
    using C = std::complex<double>;  // double: the κ² terms cancel badly in float near grazing
    const double ci = std::clamp(double(cosThetaI), 0.0, 1.0);
    const C n(eta, k);
    if (std::norm(n) == 0.0) return 1.0f;  // |η + iκ| → 0 limit (gaps in measured data read as 0)
    const double sin2I = 1.0 - ci * ci;
    const C sin2T = sin2I / (n * n);
    const C ct = std::sqrt(C(1.0) - sin2T);
    const C rPerp = (ci - n * ct) / (ci + n * ct);
    const C rPar = (n * ci - ct) / (n * ci + ct);
    return float(0.5 * (std::norm(rPerp) + std::norm(rPar)));
}

/// Schlick 1994, "An Inexpensive BRDF Model for Physically-based Rendering", eq. 15:
///   F ≈ F0 + (1 − F0)(1 − cosθ)⁵.
inline float fresnelSchlick(float cosTheta, float f0) {
    const float m = std::clamp(1.0f - std::abs(cosTheta), 0.0f, 1.0f);
    const float m2 = m * m;
    return f0 + (1.0f - f0) * m2 * m2 * m;
}

/// Normal-incidence reflectance of a dielectric with relative index eta: ((η−1)/(η+1))².
inline float schlickF0FromEta(float eta) { return sqr((eta - 1.0f) / (eta + 1.0f)); }

// ---- SampledSpectrum overloads (per wavelength) ----

inline SampledSpectrum fresnelDielectric(float cosThetaI, const SampledSpectrum& eta) {
    SampledSpectrum r(eta.size());
    for (int i = 0; i < eta.size(); ++i) r[i] = fresnelDielectric(cosThetaI, eta[i]);
    return r;
}

inline SampledSpectrum fresnelConductor(float cosThetaI, const SampledSpectrum& eta, const SampledSpectrum& k) {
    SampledSpectrum r(eta.size());
    for (int i = 0; i < eta.size(); ++i) r[i] = fresnelConductor(cosThetaI, eta[i], k[i]);
    return r;
}

inline SampledSpectrum fresnelSchlick(float cosTheta, const SampledSpectrum& f0) {
    SampledSpectrum r(f0.size());
    for (int i = 0; i < f0.size(); ++i) r[i] = fresnelSchlick(cosTheta, f0[i]);
    return r;
}

// ---- Directions ----

/// Refraction of w (pointing away from the surface) through a (micro)surface with unit normal m,
/// given cosThetaT and etaTI from fresnelDielectricFull(dot(w, m), eta):
///   t = m (etaTI (w·m) + cosθt) − etaTI w   (Walter et al. 2007 eq. 40, Mitsuba sign convention).
inline vec3 refract(const vec3& w, const vec3& m, float cosThetaT, float etaTI) {
    return m * (etaTI * glm::dot(w, m) + cosThetaT) - w * etaTI;
}
/// Refraction about the local normal (0,0,1).
inline vec3 refractLocal(const vec3& w, float cosThetaT, float etaTI) {
    return vec3(-etaTI * w.x, -etaTI * w.y, cosThetaT);
}

}  // namespace iris
