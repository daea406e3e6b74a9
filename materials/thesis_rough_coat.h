// The pieces of the rough plastic model (Jakob; thesis 000 §2.5) shared by `roughplastic` and
// the thesis' proposed model (§3.2), written as scalar functions of one relative index η so that
// both materials perform exactly the same floating-point operations per channel.
//
// Model (derived in docs/thesis_models.md): a rough dielectric coat (relative index η, roughness
// α) over a Lambertian base of albedo ρ. In our convention (eval without the cosine):
//   f(wo, wi) = ks · F(wo·h, η) D(h) G(wo, wi, h) / (4 μi μo)                 (eqs. 2.36, 3.15)
//             + ρ' · T(η, α, μi) T(η, α, μo) / (π η²)                        (eqs. 2.55, 3.16)
//   ρ' = ρ / (1 − Fdr)       (linear, the thesis' eq. 2.55 with its "Rd" = Fdr, Mitsuba default)
//   ρ' = ρ / (1 − ρ Fdr)     (nonlinear: the geometric series of internal bounces)
//   Fdr = 1 − Td(η, α): internal diffuse reflectance of the coat (eq. 2.54 / 3.19).
#pragma once

#include "core/sampling.h"
#include "materials/fresnel.h"
#include "materials/microfacet.h"
#include "materials/rough_plastic_tables.h"

namespace iris {

/// The η-independent part of the coat's specular reflection: half vector h and D G/(4 μi μo).
struct RoughCoatGeometry {
    vec3 h{0, 0, 1};
    float dg = 0.0f;
};
/// Normalised half vector h = (wo + wi)/|wo + wi| of a reflection; false when wo + wi vanishes.
inline bool roughCoatHalfVector(const vec3& wo, const vec3& wi, vec3& h) {
    h = wo + wi;
    const float len = glm::length(h);
    if (!(len > 0)) return false;
    h /= len;
    return true;
}

inline RoughCoatGeometry roughCoatGeometry(const MicrofacetDistribution& dist, const vec3& wo, const vec3& wi) {
    RoughCoatGeometry g;
    if (wo.z <= 0 || wi.z <= 0 || !roughCoatHalfVector(wo, wi, g.h)) return RoughCoatGeometry{};
    g.dg = dist.D(g.h) * dist.G(wi, wo, g.h) / (4.0f * wi.z * wo.z);
    return g;
}

/// roughCoatGeometry with wo's factor of the separable Smith G precomputed, g1o = 1/(1 + Λ(wo)):
/// G(wi, wo, h) = G1(wi, h) · χ+(wo·h) g1o ([W07] eq. 23). For a distribution with
/// ShadowingModel::SmithSeparable and the exact Smith G1 (the default the coat models create) this
/// performs the same float operations as roughCoatGeometry(dist, wo, wi), so the result is equal.
inline RoughCoatGeometry roughCoatGeometry(const MicrofacetDistribution& dist, const vec3& wo, const vec3& wi,
                                           float g1o) {
    RoughCoatGeometry g;
    if (wo.z <= 0 || wi.z <= 0 || !roughCoatHalfVector(wo, wi, g.h)) return RoughCoatGeometry{};
    const float g1wo = glm::dot(wo, g.h) * wo.z <= 0 ? 0.0f : g1o;  // MicrofacetDistribution::smithG1
    g.dg = dist.D(g.h) * (dist.G1(wi, g.h) * g1wo) / (4.0f * wi.z * wo.z);
    return g;
}

/// The half vector of a (wo, wi) pair and D(h), for a BSDF whose eval and pdf see the same pair
/// (the integrators call both; materials/thesis/proposed.cpp caches this per pair). ok == false: wo + wi
/// vanishes (no h).
struct RoughCoatHalf {
    vec3 h{0, 0, 1};
    bool ok = false;
    float d = 0.0f;  // D(h) when ok
};
inline RoughCoatHalf roughCoatHalf(const MicrofacetDistribution& dist, const vec3& wo, const vec3& wi) {
    RoughCoatHalf r;
    r.ok = roughCoatHalfVector(wo, wi, r.h);
    if (r.ok) r.d = dist.D(r.h);
    return r;
}
/// roughCoatGeometry(dist, wo, wi, g1o) with h and D(h) from hd = roughCoatHalf(dist, wo, wi):
/// the same float operations, so the same result.
inline RoughCoatGeometry roughCoatGeometry(const MicrofacetDistribution& dist, const vec3& wo, const vec3& wi,
                                           float g1o, const RoughCoatHalf& hd) {
    RoughCoatGeometry g;
    if (wo.z <= 0 || wi.z <= 0 || !hd.ok) return RoughCoatGeometry{};
    g.h = hd.h;
    const float g1wo = glm::dot(wo, g.h) * wo.z <= 0 ? 0.0f : g1o;  // MicrofacetDistribution::smithG1
    g.dg = hd.d * (dist.G1(wi, g.h) * g1wo) / (4.0f * wi.z * wo.z);
    return g;
}

/// Specular microfacet reflection of the coat without weight: F(wo·h, η) · D G/(4 μi μo)
/// (eqs. 2.6, 2.36, 3.15).
inline float roughCoatSpecular(const RoughCoatGeometry& g, const vec3& wo, float eta) {
    return g.dg > 0 ? fresnelDielectric(glm::dot(wo, g.h), eta) * g.dg : 0.0f;
}

/// Diffuse path through the coat without the base albedo: T12 T21 / (π η²)  (eq. 2.55), from the
/// two transmittances T12 = T(η, α, cosθi), T21 = T(η, α, cosθo).
inline float roughCoatDiffuse(float t12, float t21, float eta) { return t12 * t21 * kInvPi / (eta * eta); }

/// T(η_c, α, μ) for the channels c of one BSDF, read (constant α) from collapsed μ-lines (one per
/// channel, RoughTablesAtAlpha::collapse; RGB mode), from the α-collapsed tables with one η stencil
/// per channel (RoughTablesAtAlpha::transmittance; spectral mode, bit-equal to the lines), or, in
/// general (textured α), from the (η, α) stencils of the full tables. All interpolate the same
/// tables (eq. 2.44); the collapsed forms do the stencil sums once, so they agree with the
/// general one up to float rounding.
struct RoughCoatChannels {
    const RoughTransmittanceTables* tables = nullptr;
    const RoughTransmittanceTables::Line* stencils = nullptr;  // general: one per channel
    const float* lines = nullptr;                                // collapsed: channel c at lines + c·nMu
    const RoughTablesAtAlpha* atAlpha = nullptr;                 // with etaStencils: one per channel
    const RoughStencil* etaStencils = nullptr;
    const RoughEtaRows* etaRows = nullptr;                       // optional: etaStencils prepared for SIMD
    int nMu = 0;

    /// T of channels 0..n−1 at μ = cosTheta, into out[0..n).
    void transmittance(float cosTheta, int n, float* out) const {
        if (lines) {
            const RoughStencil s = roughMuStencil(cosTheta, nMu);  // shared by all channels
            for (int c = 0; c < n; ++c) out[c] = roughLineTransmittance(lines + size_t(c) * size_t(nMu), s);
        } else if (etaStencils) {  // channels side by side, equal to atAlpha->transmittance per channel
            atAlpha->transmittances(etaStencils, etaRows, n, roughMuStencil(cosTheta, nMu), out);
        } else {
            for (int c = 0; c < n; ++c) out[c] = tables->transmittance(stencils[c], cosTheta);
        }
    }
};

/// Effective base albedo ρ' (linear: ρ/(1 − Fdr); nonlinear: ρ/(1 − ρ Fdr)).
inline float roughCoatAlbedo(float rho, float fdr, bool nonlinear) {
    return nonlinear ? rho / (1.0f - rho * fdr) : rho / (1.0f - fdr);
}

/// Probability of sampling the specular lobe given wo: the share of the (average) specular
/// weight times the coat's reflectance 1 − T12(μo) against the (average) diffuse weight times T12.
inline float roughCoatSpecularProbability(float ksAvg, float rhoAvg, float t12Avg) {
    const float a = ksAvg * (1.0f - t12Avg), b = rhoAvg * t12Avg;
    if (!(a + b > 0)) return ksAvg > 0 ? 1.0f : 0.0f;
    return std::clamp(a / (a + b), 0.0f, 1.0f);
}

/// Density of reflecting wo about a visible-normal sample: D_wo(h) / (4 |wo·h|).
inline float roughCoatSpecularPdf(const MicrofacetDistribution& dist, const vec3& wo, const vec3& wi) {
    vec3 h;
    if (!roughCoatHalfVector(wo, wi, h)) return 0.0f;
    const float woh = glm::dot(wo, h);
    if (woh <= 0) return 0.0f;
    return dist.pdf(wo, h) / (4.0f * woh);
}

/// roughCoatSpecularPdf with wo's Smith G1 factor g1o = 1/(1 + Λ(wo)) precomputed, for wo.z > 0
/// and visible-normal sampling: G1(wo, h) (wo·h)₊ D(h)/wo.z ([HD14] eq. 2) over 4 (wo·h). The
/// same float operations as roughCoatSpecularPdf(dist, wo, wi) (MicrofacetDistribution::pdf).
inline float roughCoatSpecularPdf(const MicrofacetDistribution& dist, const vec3& wo, const vec3& wi, float g1o) {
    vec3 h;
    if (!roughCoatHalfVector(wo, wi, h)) return 0.0f;
    const float woh = glm::dot(wo, h);
    if (woh <= 0) return 0.0f;
    const float g1 = woh * wo.z <= 0 ? 0.0f : g1o;  // χ+ of smithG1(wo, h)
    return g1 * std::max(0.0f, woh) * dist.D(h) / wo.z / (4.0f * woh);
}

/// roughCoatSpecularPdf(dist, wo, wi, g1o) with h and D(h) from hd = roughCoatHalf(dist, wo, wi):
/// the same float operations, so the same result.
inline float roughCoatSpecularPdf(const vec3& wo, float g1o, const RoughCoatHalf& hd) {
    if (!hd.ok) return 0.0f;
    const float woh = glm::dot(wo, hd.h);
    if (woh <= 0) return 0.0f;
    const float g1 = woh * wo.z <= 0 ? 0.0f : g1o;  // χ+ of smithG1(wo, h)
    return g1 * std::max(0.0f, woh) * hd.d / wo.z / (4.0f * woh);
}

}  // namespace iris
