// Cloth BRDF: Charlie microfibre sheen over a (wrapped) diffuse base with a subsurface colour,
// the model of Filament's cloth material (Guy & Agopian, "Physically Based Rendering in Filament",
// §4.12.2) as used by thesis 004 (§5.2, eqs. 5.1–5.4), in path-tracing form.
//
//   f = f_d + f_sheen                                   (Filament: color = Fd + Fr·n·l)
//   f_sheen = C_sheen · D_Charlie(α, θh) · V            no Fresnel on the sheen (thesis 004 §5.2.2)
//     V = G_Charlie / (4 cosθo cosθi)  (visibility = "charlie", default; Estevez & Kulla 2017)
//     V = 1 / (4 (cosθi + cosθo − cosθi cosθo))        (visibility = "neubelt"; Neubelt & Pettineo 2013)
//   f_d · cosθi = ρ/π · max(0, (cosθi + w)/(1 + w)²) · clamp(C_ss + cosθi, 0, 1)
//     (wrapped diffuse, Filament §4.12.2 "Fd_Wrap" with its energy-conserving (1 + w)²
//      denominator, thesis 004 eq. 5.1 and Listing 5.4 with w = 0.5; the subsurface factor
//      saturate(C_ss + n·l) is applied only when `subsurface_color` is given, as in Filament).
//   With w = 0 and no subsurface colour f_d = ρ/π (Lambert).
//
// Parameters: base_color (0.5), sheen_color (0.5), roughness α (0.5, in (0, 1]: the Charlie α
// itself, not squared), wrap w (0, ≥ 0), subsurface_color (absent), visibility ("charlie").
// Sampling: power-cosine hemisphere sampling, p ∝ cos^(1/2)θ (see cloth_distributions.h).
// The wrapped diffuse and the subsurface factor depend on wi only, so the BRDF is reciprocal only
// for w = 0 without subsurface colour; the sheen lobe alone is reciprocal.
#include "core/registry.h"
#include "materials/cloth_distributions.h"
#include "materials/cloth_sampling.h"
#include "materials/material.h"
#include "materials/textures/texture_params.h"

namespace iris {
namespace {

class ClothBSDF final : public cloth::SqrtCosineSampledBSDF {
public:
    ClothBSDF(const SampledSpectrum& base, const SampledSpectrum& sheen, const SampledSpectrum& subsurface,
              bool hasSubsurface, float alpha, float wrap, bool neubelt)
        : base_(base), sheen_(sheen), subsurface_(subsurface), hasSubsurface_(hasSubsurface), alpha_(alpha),
          wrap_(wrap), neubelt_(neubelt) {}

    SampledSpectrum eval(const vec3& wo, const vec3& wi, TransportMode mode) const override {
        // The wrapped diffuse is not reciprocal: importance transport takes the adjoint
        // f*(wo, wi) = f(wi, wo) (Veach 1997 eq. 3.21).
        if (mode == TransportMode::Importance) return eval(wi, wo, TransportMode::Radiance);
        if (wo.z <= 0 || wi.z < cloth::kMinCosTheta) return SampledSpectrum(base_.size());
        const float cosO = wo.z, cosI = wi.z;
        // Wrapped diffuse divided by cosθi (the integrator multiplies by cosθi again).
        const float wrapFactor = wrap_ == 0.0f ? 1.0f : (cosI + wrap_) / (sqr(1.0f + wrap_) * cosI);
        SampledSpectrum f = base_ * (kInvPi * wrapFactor);
        if (hasSubsurface_) f *= map(subsurface_, [cosI](float c) { return std::clamp(c + cosI, 0.0f, 1.0f); });
        // Sheen: D_Charlie · V, no Fresnel.
        const vec3 h = glm::normalize(wo + wi);
        const float d = cloth::charlieD(alpha_, h.z);
        const float v = neubelt_ ? cloth::neubeltV(cosO, cosI)
                                 : cloth::charlieG(cosO, cosI, alpha_) / (4.0f * cosO * cosI);
        return f + sheen_ * (d * v);
    }


    uint32_t flags() const override { return kBSDFReflection | kBSDFDiffuse | kBSDFGlossy; }

private:
    SampledSpectrum base_, sheen_, subsurface_;
    bool hasSubsurface_;
    float alpha_, wrap_;
    bool neubelt_;
};

class ClothMaterial final : public Material {
public:
    ClothMaterial(SpectrumTexturePtr base, SpectrumTexturePtr sheen, SpectrumTexturePtr subsurface,
                  FloatTexturePtr roughness, float wrap, bool neubelt)
        : base_(std::move(base)), sheen_(std::move(sheen)), subsurface_(std::move(subsurface)),
          roughness_(std::move(roughness)), wrap_(wrap), neubelt_(neubelt) {}

    const BSDF* getBSDF(const ShadingPoint& sp, SampledWavelengths& wl, Arena& arena) const override {
        const SampledSpectrum ss = subsurface_ ? clampZero(subsurface_->eval(sp.tex, wl)) : SampledSpectrum(wl.size());
        // Textured roughness is clamped to the range of the Λ fit; 1e-3 keeps 1/α finite.
        const float alpha = std::clamp(roughness_->eval(sp.tex), 1e-3f, 1.0f);
        return arena.make<ClothBSDF>(clampZero(base_->eval(sp.tex, wl)), clampZero(sheen_->eval(sp.tex, wl)), ss,
                                     subsurface_ != nullptr, alpha, wrap_, neubelt_);
    }

private:
    SpectrumTexturePtr base_, sheen_, subsurface_;
    FloatTexturePtr roughness_;
    float wrap_;
    bool neubelt_;
};

std::shared_ptr<Material> createCloth(const Properties& p) {
    auto base = getSpectrumTexture(p, "base_color", SpectrumKind::Reflectance, 0.5f);
    auto sheen = getSpectrumTexture(p, "sheen_color", SpectrumKind::Reflectance, 0.5f);
    SpectrumTexturePtr subsurface;
    if (p.has("subsurface_color")) subsurface = getSpectrumTexture(p, "subsurface_color", SpectrumKind::Reflectance);
    auto roughness = getFloatTexture(p, "roughness", 0.5f);
    if (const auto* c = dynamic_cast<const ConstantFloatTexture*>(roughness.get()); c && !(c->value() > 0 && c->value() <= 1))
        failAt(p.locationOf("roughness"), "cloth: roughness must be in (0, 1], got ", c->value());
    const float wrap = p.getFloat("wrap", 0.0f);
    if (!(wrap >= 0.0f)) failAt(p.locationOf("wrap"), "cloth: wrap must be >= 0, got ", wrap);
    const std::string vis = p.getString("visibility", "charlie");
    if (vis != "charlie" && vis != "neubelt")
        failAt(p.locationOf("visibility"), "cloth: visibility must be \"charlie\" or \"neubelt\", got \"", vis, "\"");
    return std::make_shared<ClothMaterial>(std::move(base), std::move(sheen), std::move(subsurface), std::move(roughness),
                                           wrap, vis == "neubelt");
}

}  // namespace

IRIS_REGISTER(MaterialRegistry, "cloth", createCloth);

}  // namespace iris
