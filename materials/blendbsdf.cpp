// Linear blend of two BSDFs (Mitsuba plugin "blendbsdf"):
//   f = (1 − w) f₀ + w f₁,  pdf = (1 − w) pdf₀ + w pdf₁,
// with the blend weight w (`weight`, a float or float texture, clamped to [0, 1] where it is looked
// up; default 0.5 as Mitsuba 3's documentation states) and exactly two nested bsdfs: w = 0 is the
// first, w = 1 the second. Their order is Mitsuba's (materials/nested_materials.h): unnamed nested
// bsdfs in document order, then named ones in the alphanumeric order of their names.
//
// Sampling chooses the first BSDF with probability 1 − w and the second with probability w, then
// samples it (Mitsuba 3, src/bsdfs/blendbsdf.cpp: the first when uc > w, with uc rescaled). What
// the sample carries depends on `convention` (core/mitsuba_convention.h; the upgrade pass gives a
// version 0.x file's blends "mitsuba0.6"; docs/scene_format.md):
//   * "mitsuba3" (default): the nested sample unchanged (its own f and pdf, so its path weight is
//     f_i cos/pdf_i), while pdf() is the blend's: an unbiased one-sample estimator, and the MIS
//     weights of emitters reached by BSDF sampling use the nested pdf, as Mitsuba 3's do (as for
//     `mask`; materials/mask.cpp).
//   * "mitsuba0.6": a sample consistent with eval and pdf (a smooth lobe's f and pdf are the blend's at the
//     sampled direction; a delta lobe's are scaled by its selection probability), so MIS weights
//     sum to one.
// A constant weight outside [0, 1] is refused (Mitsuba clamps it silently); a texture's values are
// clamped as Mitsuba does.
#include <algorithm>

#include "core/error.h"
#include "core/registry.h"
#include "materials/fresnel_mueller.h"
#include "materials/material.h"
#include "materials/nested_materials.h"
#include "materials/textures/texture_params.h"

namespace iris {
namespace {

class BlendBSDF final : public BSDF {
public:
    BlendBSDF(const BSDF* first, const BSDF* second, float weight, bool mitsuba3, int n)
        : bsdf_{first, second}, w_{1.0f - weight, weight}, mitsuba3_(mitsuba3), n_(n) {}

    SampledSpectrum eval(const vec3& wo, const vec3& wi, TransportMode mode) const override {
        SampledSpectrum f(n_);
        for (int i = 0; i < 2; ++i)
            if (bsdf_[i] && w_[i] > 0) f += bsdf_[i]->eval(wo, wi, mode) * w_[i];  // (1 − w) f₀ + w f₁
        return f;
    }
    float pdf(const vec3& wo, const vec3& wi, TransportMode mode) const override {
        float p = 0.0f;
        for (int i = 0; i < 2; ++i)
            if (bsdf_[i] && w_[i] > 0) p += w_[i] * bsdf_[i]->pdf(wo, wi, mode);
        return p;
    }
    std::optional<BSDFSample> sample(const vec3& wo, float uc, const vec2& u, TransportMode mode) const override {
        float ui;
        const int i = lobe(uc, &ui);
        if (i < 0) return std::nullopt;
        auto s = bsdf_[i]->sample(wo, ui, u, mode);
        if (!s || mitsuba3_) return s;
        if (s->isSpecular()) {  // a delta lobe: the other BSDF has no mass on this direction
            s->f *= w_[i];
            s->pdf *= w_[i];
            return s;
        }
        return sampleFromEval(wo, s->wi, s->flags, mode);
    }
    /// Polarized: (1 − w) M₀ + w M₁, sampled as sample() does.
    MuellerSpectrum evalMueller(const vec3& wo, const vec3& wi, TransportMode mode) const override {
        MuellerSpectrum M = MuellerSpectrum::depolarizer(SampledSpectrum(n_));
        for (int i = 0; i < 2; ++i)
            if (bsdf_[i] && w_[i] > 0) M += bsdf_[i]->evalMueller(wo, wi, mode) * w_[i];
        return M;
    }
    std::optional<PolarizedBSDFSample> sampleMueller(const vec3& wo, float uc, const vec2& u, TransportMode mode) const override {
        float ui;
        const int i = lobe(uc, &ui);
        if (i < 0) return std::nullopt;
        auto s = bsdf_[i]->sampleMueller(wo, ui, u, mode);
        if (!s || mitsuba3_) return s;
        if (s->s.isSpecular()) {
            s->s.f *= w_[i];
            s->s.pdf *= w_[i];
            s->M *= w_[i];
            return s;
        }
        return withEvalMueller(*this, sampleFromEval(wo, s->s.wi, s->s.flags, mode), wo, mode);
    }
    uint32_t flags() const override { return (bsdf_[0] ? bsdf_[0]->flags() : 0u) | (bsdf_[1] ? bsdf_[1]->flags() : 0u); }

private:
    /// Mitsuba 3: the first BSDF when uc > w (probability 1 − w), uc rescaled to [0, 1) in *ui; at
    /// w = 0 or 1 always the one with weight 1. −1 when that BSDF is absent.
    int lobe(float uc, float* ui) const {
        const int i = w_[1] == 0.0f || (uc > w_[1] && w_[0] > 0.0f) ? 0 : 1;
        if (!bsdf_[i] || !(w_[i] > 0)) return -1;
        *ui = std::min(i == 0 ? (uc - w_[1]) / w_[0] : uc / w_[1], 0x1.fffffep-1f);
        return i;
    }
    const BSDF* bsdf_[2];
    float w_[2];  // selection probabilities and blend factors: 1 − w, w
    bool mitsuba3_;
    int n_;
};

class BlendMaterial final : public Material {
public:
    BlendMaterial(FloatTexturePtr weight, std::shared_ptr<Material> first, std::shared_ptr<Material> second, bool mitsuba3)
        : weight_(std::move(weight)), first_(std::move(first)), second_(std::move(second)), mitsuba3_(mitsuba3) {}

    const BSDF* getBSDF(const ShadingPoint& sp, SampledWavelengths& wl, Arena& arena) const override {
        const float w = std::clamp(weight_->eval(sp.tex), 0.0f, 1.0f);
        const BSDF* a = w < 1.0f ? first_->getBSDF(sp, wl, arena) : nullptr;
        const BSDF* b = w > 0.0f ? second_->getBSDF(sp, wl, arena) : nullptr;
        if (!a && !b) return nullptr;
        return arena.make<BlendBSDF>(a, b, w, mitsuba3_, wl.size());
    }
    bool perturbsShading() const override { return first_->perturbsShading() || second_->perturbsShading(); }

private:
    FloatTexturePtr weight_;
    std::shared_ptr<Material> first_, second_;
    bool mitsuba3_;
};

std::shared_ptr<Material> createBlendBSDF(const Properties& p) {
    auto nested = createNestedMaterials(p, "blendbsdf", {"weight", "convention"});
    if (nested.size() != 2)
        failAt(p.location(), "blendbsdf: expected two nested bsdfs, got ", nested.size(),
               " (Mitsuba: \"Two child BSDFs must be specified!\")");
    FloatTexturePtr weight = getFloatTexture(p, "weight", 0.5f);
    if (weight->isConstant()) {
        const float w = weight->eval(TextureQuery{});
        if (!(w >= 0.0f && w <= 1.0f)) failAt(p.locationOf("weight"), "blendbsdf: weight ", w, " is outside [0, 1]");
    }
    return std::make_shared<BlendMaterial>(weight, nested[0], nested[1],
                                          getConvention(p) == MitsubaConvention::Mitsuba3);
}

}  // namespace

IRIS_REGISTER(MaterialRegistry, "blendbsdf", createBlendBSDF);

}  // namespace iris
