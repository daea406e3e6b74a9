// Microfacet normal distributions (Beckmann, GGX; anisotropic αx, αy), Smith masking-shadowing,
// the Cook-Torrance V-cavity term, and normal sampling (all normals or visible normals).
//
// Everything is in the local shading frame (macro normal +z). A MicrofacetDistribution is a small,
// trivially copyable value: BSDFs store it by value in the arena.
//
// References:
//   [W07]  Walter, Marschner, Li, Torrance 2007, "Microfacet Models for Refraction through Rough
//          Surfaces" (EGSR) — D (eqs. 25, 33), Smith G1 (eqs. 27, 34), sampling (eqs. 28, 35).
//   [H14]  Heitz 2014, "Understanding the Masking-Shadowing Function in Microfacet-Based BRDFs"
//          (JCGT 3(2)) — Λ (eqs. 72, 86), height-correlated G2 (eq. 99), anisotropy (§5.3).
//   [HD14] Heitz, d'Eon 2014, "Importance Sampling Microfacet-Based BSDFs using the Distribution
//          of Visible Normals" (EGSR) — visible-normal sampling via slopes (§4, appendix).
//   [H18]  Heitz 2018, "Sampling the GGX Distribution of Visible Normals" (JCGT 7(4)), listing 1.
//   [CT82] Cook, Torrance 1982, "A Reflectance Model for Computer Graphics" — V-cavity G.
//   Thesis 000 eqs. 2.10 (Beckmann D), 2.12–2.14 (G ≈ G1 G1, rational G1), 2.19–2.22 (sampling).
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "core/frame.h"
#include "core/math.h"
#include "core/properties.h"
#include "materials/textures/texture.h"

namespace iris {

enum class MicrofacetType : uint8_t { Beckmann, GGX };

/// How the masking-shadowing term G(wi, wo, m) is computed.
enum class ShadowingModel : uint8_t {
    SmithSeparable,        // G1(wi) G1(wo)  (thesis 000 eq. 2.12, [W07] eq. 23)
    SmithHeightCorrelated, // 1 / (1 + Λ(wi) + Λ(wo))  ([H14] eq. 99)
    VCavity,               // Cook & Torrance 1982 (thesis 003): min(1, 2(n·m)(n·wo)/(wo·m), 2(n·m)(n·wi)/(wo·m))
};

class MicrofacetDistribution {
public:
    MicrofacetDistribution() = default;
    MicrofacetDistribution(MicrofacetType type, float alphaX, float alphaY, bool sampleVisible = true,
                           ShadowingModel shadowing = ShadowingModel::SmithSeparable,
                           bool beckmannRationalG1 = false)
        : type_(type), ax_(clampAlpha(alphaX)), ay_(clampAlpha(alphaY)), sampleVisible_(sampleVisible),
          shadowing_(shadowing), rational_(beckmannRationalG1) {}

    /// Parse Mitsuba's `distribution` value: "beckmann" or "ggx" (throws iris::Error otherwise).
    static MicrofacetType parseType(const std::string& name);

    MicrofacetType type() const { return type_; }
    float alphaX() const { return ax_; }
    float alphaY() const { return ay_; }
    bool sampleVisible() const { return sampleVisible_; }
    ShadowingModel shadowing() const { return shadowing_; }
    bool isIsotropic() const { return ax_ == ay_; }

    /// Normal distribution D(m) (density of microfacet area per unit solid angle of m),
    /// normalised so that ∫ D(m) cosθm dωm = 1. Zero for m.z <= 0.
    ///   Beckmann: exp(−tan²θ (cos²φ/αx² + sin²φ/αy²)) / (π αx αy cos⁴θ)   (thesis eq. 2.10, [W07] eq. 25)
    ///   GGX:      1 / (π αx αy cos⁴θ (1 + tan²θ (cos²φ/αx² + sin²φ/αy²))²)   ([W07] eq. 33, [H14] eq. 85)
    float D(const vec3& m) const;

    /// Smith Λ(w) (exact for both distributions, [H14] eqs. 72 and 86 with the anisotropic
    /// α(φ) = sqrt(cos²φ αx² + sin²φ αy²), [H14] eq. 80). Beckmann values below 2⁻²⁶ (α² tan²θ ≤ 0.08)
    /// are returned as 0: they vanish wherever Λ is added to 1 in float, which is how it is used.
    float Lambda(const vec3& w) const;

    /// Exact Smith G1(w, m) = χ+((w·m)/(w·n)) / (1 + Λ(w)). Used by the visible-normal pdf.
    float smithG1(const vec3& w, const vec3& m) const;

    /// G1 as used by G(): the exact Smith G1, or for Beckmann with the rational option the
    /// approximation of thesis 000 eqs. 2.13–2.14 ([W07] eq. 27).
    float G1(const vec3& w, const vec3& m) const;

    /// Masking-shadowing G(wi, wo, m) according to shadowing().
    float G(const vec3& wi, const vec3& wo, const vec3& m) const;

    /// Sample a microfacet normal (always m.z > 0). Visible normals of wo ([H18] for GGX,
    /// [HD14] with a numerical inversion for Beckmann) when sampleVisible(), else D(m) cosθm
    /// (thesis 000 eqs. 2.19–2.20, [W07] eqs. 28, 35). wo below the surface is mirrored to the
    /// upper side first (used from inside dielectrics).
    vec3 sampleNormal(const vec3& wo, const vec2& u) const;

    /// Density of sampleNormal per solid angle of m:
    ///   visible: G1(wo', m) max(0, wo'·m) D(m) / |wo'.z|   ([HD14] eq. 2, wo' = wo mirrored up)
    ///   all:     D(m) cosθm
    float pdf(const vec3& wo, const vec3& m) const;

private:
    static float clampAlpha(float a) { return std::max(a, 1e-4f); }
    vec3 sampleAllNormals(const vec2& u) const;
    vec3 sampleVisibleGGX(const vec3& wo, const vec2& u) const;
    vec3 sampleVisibleBeckmann(const vec3& wo, const vec2& u) const;

    MicrofacetType type_ = MicrofacetType::GGX;
    float ax_ = 0.1f, ay_ = 0.1f;
    bool sampleVisible_ = true;
    ShadowingModel shadowing_ = ShadowingModel::SmithSeparable;
    bool rational_ = false;
};

// ---- Roughness conventions ----

/// Disney/Burley perceptual roughness r to α = r² (Burley 2012 §5.4).
inline float alphaFromPerceptualRoughness(float r) { return r * r; }
/// Phong exponent e to the Beckmann α with the same highlight width, α = sqrt(2/(e+2)) ([W07] §5.2).
/// (Thesis 000 §4 uses the looser α ≈ sqrt(2/e).)
inline float beckmannAlphaFromPhongExponent(float e) { return std::sqrt(2.0f / (e + 2.0f)); }
/// Inverse of beckmannAlphaFromPhongExponent: e = 2/α² − 2.
inline float phongExponentFromBeckmannAlpha(float a) { return 2.0f / (a * a) - 2.0f; }

/// Inverse error function (Giles 2010, "Approximating the erfinv function", single-precision
/// polynomial, refined by two Newton steps in double). Exposed for tests.
double erfInv(double x);

// ---- Scene parameters (Mitsuba conventions) ----

/// The microfacet parameters of a rough material as read from a scene:
///   distribution  "beckmann" | "ggx" (default given by the plugin; Mitsuba: "beckmann")
///   alpha         isotropic roughness α (float or texture; default 0.1), or
///   alpha_u, alpha_v  anisotropic α along the tangent / bitangent (both required together)
///   sample_visible    visible-normal sampling (default true)
///   masking       "separable" (default) | "height_correlated" | "vcavity"   (iris extension)
///   beckmann_rational_g1  use thesis 000 eqs. 2.13–2.14 for Beckmann's G1 (default false; iris extension)
/// A reflection sampled through the distribution: the microfacet normal m, ωo·m > 0, the mirrored
/// direction ωi (upper hemisphere), the density pdfM of m and D(m) G(ωi, ωo, m). Everything is at
/// the sampled m — recomputing it as normalize(ωo + ωi) cancels in float near grazing angles and
/// would pair f and pdf of different normals.
struct MicrofacetReflection {
    vec3 m, wi;
    float wom, pdfM, DG;
    /// Density of ωi: the half-vector → ωi Jacobian 1/(4 ωo·m) (Walter et al. 2007, eq. 14).
    float pdf() const { return pdfM / (4.0f * wom); }
};
/// Sample m from `d` (u in [0,1)²) and reflect ωo about it; nullopt when m faces away from ωo or
/// ωi falls below the surface.
inline std::optional<MicrofacetReflection> sampleMicrofacetReflection(const MicrofacetDistribution& d, const vec3& wo,
                                                                      const vec2& u) {
    MicrofacetReflection r;
    r.m = d.sampleNormal(wo, u);
    r.wom = glm::dot(wo, r.m);
    if (r.wom <= 0) return std::nullopt;
    r.wi = reflect(wo, r.m);
    if (r.wi.z <= 0) return std::nullopt;
    r.pdfM = d.pdf(wo, r.m);
    r.DG = d.D(r.m) * d.G(r.wi, wo, r.m);
    return r;
}

struct MicrofacetParams {
    MicrofacetType type = MicrofacetType::Beckmann;
    FloatTexturePtr alphaU, alphaV;
    bool sampleVisible = true;
    ShadowingModel shadowing = ShadowingModel::SmithSeparable;
    bool rational = false;

    static MicrofacetParams read(const Properties& p, const std::string& defaultDistribution = "beckmann",
                                 float defaultAlpha = 0.1f);
    MicrofacetDistribution at(const TextureQuery& q) const {
        return MicrofacetDistribution(type, alphaU->eval(q), alphaV->eval(q), sampleVisible, shadowing, rational);
    }
};

}  // namespace iris
