// Scalar terms of the Disney "principled" BRDF that are specific to it (the GGX lobes themselves
// come from materials/microfacet.h). Exposed in a header so the tests can check them directly.
//
// Reference: [B12] B. Burley, "Physically-Based Shading at Disney", SIGGRAPH 2012 course
// "Practical Physically Based Shading in Film and Game Production" (revised Aug 31 2012), §5 and
// Appendix B, and its reference implementation `disney.brdf` in the Disney BRDF Explorer.
#pragma once

#include <cmath>

#include "core/math.h"

namespace iris::principled {

/// Schlick's weight (1 − cosθ)^5 (Schlick 1994; [B12] §5.3 and §5.5).
inline float schlickWeight(float cosTheta) {
    const float m = std::clamp(1.0f - cosTheta, 0.0f, 1.0f);
    const float m2 = m * m;
    return m2 * m2 * m;
}

/// Burley diffuse retro-reflection factor ([B12] §5.3):
///   (1 + (F_D90 − 1)(1 − cosθl)^5)(1 + (F_D90 − 1)(1 − cosθv)^5),  F_D90 = 0.5 + 2 roughness cos²θd.
/// The diffuse BRDF is baseColor/π times this factor.
inline float burleyDiffuseFactor(float cosL, float cosV, float cosD, float roughness) {
    const float fd90 = 0.5f + 2.0f * roughness * cosD * cosD;
    return (1.0f + (fd90 - 1.0f) * schlickWeight(cosL)) * (1.0f + (fd90 - 1.0f) * schlickWeight(cosV));
}

/// Hanrahan–Krueger-inspired subsurface factor ([B12] §5.3, `disney.brdf`):
///   F_ss90 = roughness cos²θd,  F_ss = (1 + (F_ss90 − 1)(1 − cosθl)^5)(1 + (F_ss90 − 1)(1 − cosθv)^5),
///   ss = 1.25 (F_ss (1/(cosθl + cosθv) − 0.5) + 0.5).
/// The subsurface BRDF is baseColor/π times ss. (Thesis 003 writes 1/(cosθl·cosθv): a typo.)
inline float subsurfaceFactor(float cosL, float cosV, float cosD, float roughness) {
    const float fss90 = roughness * cosD * cosD;
    const float fss = (1.0f + (fss90 - 1.0f) * schlickWeight(cosL)) * (1.0f + (fss90 - 1.0f) * schlickWeight(cosV));
    return 1.25f * (fss * (1.0f / (cosL + cosV) - 0.5f) + 0.5f);
}

/// GTR with γ = 1 ("GTR1", Berry), used by the clearcoat ([B12] §5.4 eq. 4 with its corrected
/// normalisation, Appendix B.2):  D = (α² − 1) / (π ln(α²) (1 + (α² − 1) cos²θh)),
/// normalised so that ∫ D cosθh dω = 1; the α → 1 limit is 1/π.
inline float gtr1D(float cosThetaH, float alpha) {
    if (cosThetaH <= 0.0f) return 0.0f;
    const float a2 = alpha * alpha;
    if (a2 >= 1.0f - 1e-6f) return kInvPi;
    const float t = 1.0f + (a2 - 1.0f) * cosThetaH * cosThetaH;
    return (a2 - 1.0f) / (kPi * std::log(a2) * t);
}

/// Sample a microfacet normal from D_GTR1 cosθh ([B12] Appendix B.2):
///   φ = 2π u1,  cos²θh = (1 − α^(2(1 − u0))) / (1 − α²).
inline vec3 sampleGTR1(const vec2& u, float alpha) {
    const float a2 = alpha * alpha;
    const float cos2 = a2 >= 1.0f - 1e-6f ? 1.0f - u.x : (1.0f - std::pow(a2, 1.0f - u.x)) / (1.0f - a2);
    const float cosT = safeSqrt(cos2), sinT = safeSqrt(1.0f - cos2);
    const float phi = 2.0f * kPi * u.y;
    return vec3(sinT * std::cos(phi), sinT * std::sin(phi), cosT);
}

/// Clearcoat α from clearcoatGloss ([B12] §5.4): α = mix(0.1, 0.001, gloss).
inline float clearcoatAlpha(float gloss) { return lerp(gloss, 0.1f, 0.001f); }

/// Anisotropic GGX roughnesses ([B12] addendum "anisotropic"; `disney.brdf`): aspect = sqrt(1 − 0.9 anisotropic),
/// αx = roughness²/aspect, αy = roughness²·aspect, both at least 0.001 (as in `disney.brdf`).
inline vec2 anisotropicAlphas(float roughness, float anisotropic) {
    const float aspect = std::sqrt(1.0f - 0.9f * anisotropic);
    const float a = roughness * roughness;
    return vec2(std::max(0.001f, a / aspect), std::max(0.001f, a * aspect));
}

/// Luminance of a linear Rec.709 RGB triple (CIE Y, ITU-R BT.709 weights). Burley's
/// `disney.brdf` uses the rounded weights (0.3, 0.6, 0.1); we use the exact Rec.709 Y.
inline float luminance(const vec3& rgb) { return 0.2126f * rgb.x + 0.7152f * rgb.y + 0.0722f * rgb.z; }

// ---- Mitsuba 3's principled / principledthin (materials/principled_mitsuba.cpp) ----
// [B15] B. Burley, "Extending the Disney BRDF to a BSDF with Integrated Subsurface Scattering",
// SIGGRAPH 2015 course "Physically Based Shading in Theory and Practice"; Mitsuba 3,
// src/bsdfs/principled.cpp, principledthin.cpp, principledhelpers.h.

/// Rec.709 luminance with the weights Mitsuba 3 uses (include/mitsuba/core/spectrum.h, `luminance`
/// of a Color3: the Y row of its sRGB → XYZ matrix).
inline float luminanceMitsuba(const vec3& rgb) { return 0.212671f * rgb.x + 0.715160f * rgb.y + 0.072169f * rgb.z; }

/// The Schlick weight w of Mitsuba 3's `calc_schlick(R0, cosθ, η)`, F = R0 + (1 − R0) w: for a
/// relative index η_it > 1 on cosθ's side w = (1 − |cosθ|)^5; otherwise (light arriving from the
/// denser side) the transmitted cosine is used, w = (1 − cosθt)^5 with sin²θt = η_it⁻² sin²θ
/// (cosθt = 0 under total internal reflection, so F = 1) — Schlick 1994's rule that his
/// approximation takes the angle on the less dense side.
inline float schlickWeightMitsuba(float cosTheta, float eta) {
    const float etaIT = cosTheta >= 0.0f ? eta : 1.0f / eta;
    if (etaIT > 1.0f) return schlickWeight(std::abs(cosTheta));
    const float etaTI = 1.0f / etaIT;
    const float cos2T = 1.0f - (1.0f - cosTheta * cosTheta) * etaTI * etaTI;
    return schlickWeight(safeSqrt(cos2T));
}

/// Mitsuba 3's `specular` → η (principled.cpp): the inverse of 0.08 specular = ((η − 1)/(η + 1))²,
/// η = 2 / (1 − sqrt(0.08 specular)) − 1 ([B15] §5.1 relates specular and η the same way).
inline float etaFromSpecular(float specular) { return 2.0f / (1.0f - std::sqrt(0.08f * specular)) - 1.0f; }

/// [B15] §5.3 eqs. 4–5, as Mitsuba 3 writes Burley's diffuse: the Lambertian part with the
/// Fresnel-like darkening, f_d = (1 − F_L/2)(1 − F_V/2), plus the retro-reflection
/// f_retro = R_R (F_L + F_V + F_L F_V (R_R − 1)), R_R = 2 roughness cos²θd, F_x = (1 − cosθx)^5.
/// Algebraically equal to burleyDiffuseFactor ([B12]) with F_D90 = 0.5 + R_R.
inline float burley2015DiffuseFactor(float cosL, float cosV, float cosD, float roughness) {
    const float fl = schlickWeight(cosL), fv = schlickWeight(cosV);
    const float rr = 2.0f * roughness * cosD * cosD;
    return (1.0f - 0.5f * fl) * (1.0f - 0.5f * fv) + rr * (fl + fv + fl * fv * (rr - 1.0f));
}

/// [B15] Figure 15 as Mitsuba 3's principledthin applies it: the roughness of the thin-surface
/// transmission lobe, (0.65 η − 0.35) roughness.
inline float thinTransmissionRoughness(float eta, float roughness) { return (0.65f * eta - 0.35f) * roughness; }

}  // namespace iris::principled
