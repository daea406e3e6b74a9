// Microfibre ("sheen") distributions and their shadowing/visibility terms, shared by the `cloth`
// and `velvet` materials and their tests. All angles are in the local shading frame (normal +z).
//
// References:
//   [EK17]  A. Conty Estevez, C. Kulla, "Production Friendly Microfacet Sheen BRDF", Sony Pictures
//           Imageworks technical report / SIGGRAPH 2017 course "Revisiting Physically Based
//           Shading at Imageworks".
//   [NP13]  D. Neubelt, M. Pettineo, "Crafting a Next-Gen Material Pipeline for The Order: 1886",
//           SIGGRAPH 2013 course "Physically Based Shading in Theory and Practice".
//   [APS00] M. Ashikhmin, S. Premože, P. Shirley, "A Microfacet-based BRDF Generator", SIGGRAPH 2000.
//   [Ash07] M. Ashikhmin, "Distribution-based BRDFs", technical report, 2007.
#pragma once

#include <cmath>

#include "core/math.h"
#include "core/sampling.h"

namespace iris::cloth {

/// Charlie sheen distribution [EK17, §2]: D(θh) = (2 + 1/α) sin(θh)^(1/α) / (2π).
/// Normalised so that ∫ D cosθh dω = 1 over the hemisphere (checked in tests/materials/test_cloth.cpp).
inline float charlieD(float alpha, float cosThetaH) {
    const float invAlpha = 1.0f / alpha;
    const float sin2 = std::max(0.0f, 1.0f - cosThetaH * cosThetaH);
    return (2.0f + invAlpha) * std::pow(sin2, 0.5f * invAlpha) * kInv2Pi;
}

/// The fitted exponent L(x) = a / (1 + b x^c) + d x + e of the Charlie Λ [EK17, §3, fit table];
/// the five coefficients are interpolated between their r = 0 and r = 1 fits with weight
/// t = (1 − r)² (t = 1 at r = 0): p = (1 − t)·p(r=1) + t·p(r=0).
inline float charlieL(float x, float alpha) {
    const float t = sqr(1.0f - alpha);
    const float a = lerp(t, 21.5473f, 25.3245f);
    const float b = lerp(t, 3.82987f, 3.32435f);
    const float c = lerp(t, 0.19823f, 0.16801f);
    const float d = lerp(t, -1.97760f, -1.27393f);
    const float e = lerp(t, -4.32054f, -4.85967f);
    return a / (1.0f + b * std::pow(x, c)) + d * x + e;
}

/// Smith Λ of the Charlie distribution, fitted [EK17, §3]:
///   Λ(θ) = exp(L(cosθ))                   for cosθ < 0.5,
///   Λ(θ) = exp(2 L(0.5) − L(1 − cosθ))    otherwise (the fit is mirrored about 0.5).
inline float charlieLambda(float cosTheta, float alpha) {
    const float c = std::abs(cosTheta);
    if (c < 0.5f) return std::exp(charlieL(c, alpha));
    return std::exp(2.0f * charlieL(0.5f, alpha) - charlieL(1.0f - c, alpha));
}

/// Height-correlated masking-shadowing with the fitted Λ [EK17, §3]: G = 1 / (1 + Λ(wo) + Λ(wi)).
inline float charlieG(float cosO, float cosI, float alpha) {
    return 1.0f / (1.0f + charlieLambda(cosO, alpha) + charlieLambda(cosI, alpha));
}

/// Neubelt visibility [NP13], the replacement of G / (4 cosθo cosθi) by a smooth denominator:
///   V = 1 / (4 (n·l + n·v − (n·l)(n·v))).
/// (Ashikhmin 2007 uses the same denominator for the velvet BRDF [Ash07].)
inline float neubeltV(float cosO, float cosI) {
    return 1.0f / (4.0f * (cosI + cosO - cosI * cosO));
}

/// Ashikhmin velvet distribution [APS00 (velvet example), Ash07 (offset 1 + 4·peak)] with its normalisation:
///   D(θh) = (1 + 4 exp(−cot²θh / σ²) / sin⁴θh) / (π (1 + 4σ²)),
/// ∫ D cosθh dω = 1 (the second term integrates to 4σ²; checked numerically in the tests).
inline float velvetD(float sigma, float cosThetaH) {
    const float cos2 = cosThetaH * cosThetaH;
    const float sin2 = std::max(0.0f, 1.0f - cos2);
    const float s2 = sigma * sigma;
    float peak = 0.0f;
    if (sin2 > 0.0f) {
        const float cot2 = cos2 / sin2;
        // exp(−cot²/σ²)/sin⁴ → 0 as sinθh → 0: guard the 0·∞ form.
        const float ex = std::exp(-cot2 / s2);
        peak = ex > 0.0f ? 4.0f * ex / (sin2 * sin2) : 0.0f;
    }
    return (1.0f + peak) / (kPi * (1.0f + 4.0f * s2));
}

/// Directions with cosθi below this carry no energy in the cloth lobes (the wrapped diffuse
/// divides by cosθi). The excluded solid angle is ~2π·1e-7 sr.
constexpr float kMinCosTheta = 1e-7f;

/// Direction sampling shared by the cloth lobes: power-cosine hemisphere sampling with exponent
/// 1/2, p(ω) = (3/(4π)) cos^(1/2)θ, cosθ = u0^(2/3), φ = 2π u1 (inverse CDF of cos^(k)θ sinθ with
/// k = 1/2). Compared with cosine sampling it puts more samples near grazing angles, where the
/// sheen peaks and the wrapped diffuse keep f·cosθ finite as cosθ → 0: there the weight
/// f·cosθ/p grows only like cos^(−1/2)θ, so the variance stays finite (cosine sampling would
/// have weight ∝ 1/cosθ and infinite variance). The density is continuous at the horizon.
inline vec3 sampleSqrtCosineHemisphere(const vec2& u) {
    const float cosT = std::pow(u.x, 2.0f / 3.0f);
    const float sinT = safeSqrt(1.0f - cosT * cosT);
    const float phi = 2.0f * kPi * u.y;
    return vec3(sinT * std::cos(phi), sinT * std::sin(phi), cosT);
}
inline float sqrtCosineHemispherePdf(float cosTheta) {
    if (cosTheta < kMinCosTheta) return 0.0f;
    return 0.75f * kInvPi * std::sqrt(cosTheta);
}

}  // namespace iris::cloth
