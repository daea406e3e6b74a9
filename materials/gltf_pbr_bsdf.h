// The glTF 2.0 BSDF at one surface point (glTF 2.0 Appendix B; extensions as in gltf_pbr.h):
//   material = mix(dielectric_brdf, metal_brdf, metallic)                        (B.1)
//   metal_brdf = F_metal · specular_brdf(α),  F_metal = C + (1 − C)(1 − |v·h|)⁵   (B.2.1, B.3.4)
//   dielectric_brdf = (1 − s·max₃(fr)) · base + s·fr · specular_brdf(α)          (KHR_materials_specular)
//     fr = f0 + (1 − f0)(1 − |v·h|)⁵, f0 = min(((ior − 1)/(ior + 1))² · specularColor, 1)  (KHR_materials_ior)
//     base = mix(C/π, C · specular_btdf(α), transmission)                        (KHR_materials_transmission)
//   sheen:     sheenColor · D_charlie V_sheen + material · min(1 − max₃(sheenColor) E(n·v), 1 − max₃(sheenColor) E(n·l))
//   clearcoat: (1 − c·Fc) · (the above) + c·Fc · specular_brdf(α_c),  Fc = 0.04 + 0.96 (1 − |v·h|)⁵
//   iridescence: F_metal → mix(F_metal, F_film, i), s·fr → mix(s·fr, F_film, i)  (KHR_materials_iridescence)
// specular_btdf is thin-walled (no volume): the GGX lobe of the direction mirrored through the
// surface, centred on −v. With KHR_materials_volume (PbrPoint::volume) it refracts instead: the
// README's "Implementation" BTDF (Walter et al. 2007 eq. 21) at the generalised half vector
// h = −normalize(η_i v + η_o l), its Fresnel by the README's three cases (the dense side's angle,
// total internal reflection F = 1), and the back side is the same BSDF mirrored with the relative
// index 1/ior (inside the volume), whatever doubleSided says. The radiance BTDF has the viewer's
// index as η_o (Walter's convention; the README's formula, written with V on the incident side, has
// an extra η², which Importance mode applies, keeping the viewer-side Fresnel factor: not the exact
// adjoint where the two sides' Fresnel cases differ). α = roughness². The base weight of a film is exact per
// lane (1 − F) in the Exact reading and the README's max₃ in the Khr reading. Alpha coverage (mask, blend) is a
// pass-through lobe of weight 1 − opacity. Seen from behind (wo.z < 0), a double-sided material
// is the same BSDF mirrored through the surface; a single-sided one is culled (§3.9.5): a
// pass-through of weight 1.
#pragma once

#include "materials/bsdf.h"
#include "materials/gltf_pbr.h"
#include "materials/microfacet.h"
#include "spectral/sampled_spectrum.h"

namespace iris::gltf {

/// The material's inputs at one point: colours per lane (wavelength or channel) and in RGB (the
/// spec's max₃ weights read the RGB), scalars once.
struct PbrPoint {
    SampledSpectrum base, specularColor, sheenColor, lambda;  // lambda: each lane's wavelength (nm)
    vec3 baseRGB{1.0f}, specularColorRGB{1.0f};
    float sheenMax = 0, metallic = 0, alpha = 1, ior = 1.5f, specular = 1, transmission = 0;
    float clearcoat = 0, coatAlpha = 0, sheenAlpha = 0, sheenRoughness = 0;
    float iridescence = 0, thicknessNm = 0, filmIor = 1.3f, edgeTint = -1, opacity = 1;
    bool rgb = false, doubleSided = false, volume = false;
    ThinFilmRGBMode mode = ThinFilmRGBMode::Exact;
};

class PbrBSDF final : public BSDF {
public:
    explicit PbrBSDF(const PbrPoint& p);
    SampledSpectrum eval(const vec3& wo, const vec3& wi, TransportMode mode) const override;
    float pdf(const vec3& wo, const vec3& wi, TransportMode mode) const override;
    std::optional<BSDFSample> sample(const vec3& wo, float uc, const vec2& u, TransportMode mode) const override;
    uint32_t flags() const override;

private:
    enum Lobe { kDiffuse, kSpecular, kTransmission, kSheen, kCoat, kLobes };
    // The front-side functions take eta, the index beyond the surface over the viewer's side
    // (used by a volume boundary only): ior from outside, 1/ior from inside.
    /// The surface (everything but the pass-through) at v = wo, l = wi.
    SampledSpectrum surface(const vec3& wo, const vec3& wi, float eta, TransportMode mode) const;
    /// The dielectric Fresnel-weighted specular colour per lane at |v·h| = vh with Schlick weight
    /// w (< 0: total internal reflection); sets baseWeight, the weight of the base (diffuse /
    /// transmission).
    SampledSpectrum dielectricFresnel(float vh, float w, SampledSpectrum& baseWeight) const;
    SampledSpectrum metalFresnel(float vh) const;
    float surfacePdf(const vec3& wo, const vec3& wi, float eta) const;
    /// eval / pdf / sample for wo above the surface (the public ones mirror or cull the back side).
    SampledSpectrum evalFront(const vec3& wo, const vec3& wi, float eta, TransportMode mode) const;
    float pdfFront(const vec3& wo, const vec3& wi, float eta) const;
    std::optional<BSDFSample> sampleFront(const vec3& wo, float uc, const vec2& u, float eta, TransportMode mode) const;
    std::optional<BSDFSample> passThrough(const vec3& wo, float weight, float prob) const;
    /// True when the back side is evaluated as the mirrored front (doubleSided, or a volume boundary).
    bool mirrorsBack() const { return p_.doubleSided || p_.volume; }
    /// eta of the mirrored back side: inside a volume 1/ior.
    float backEta() const { return p_.volume ? 1.0f / p_.ior : p_.ior; }

    PbrPoint p_;
    MicrofacetDistribution spec_, coat_;
    float lobeProb_[kLobes] = {};
};

}  // namespace iris::gltf
