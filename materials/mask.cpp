// Opacity mask and null surface (Mitsuba plugins "mask" and "null").
//
// `mask` blends a nested BSDF with a forward-facing Dirac delta that lets the ray pass unchanged
// (wi = −wo): f = opacity · f_nested for the nested lobes, and the pass-through lobe carries
// 1 − opacity. Parameters (Mitsuba 3, src/bsdfs/mask.cpp): `opacity` (float or texture, default
// 0.5; 1 = opaque) and exactly one nested bsdf (unnamed or under any name; none is an error, as in
// Mitsuba: "Child BSDF not specified"). Both sides of the surface pass light through; the nested
// BSDF keeps its own sidedness (a one-sided nested BSDF is black from behind, its transparent part
// still transmits). `null` is the pass-through alone (Mitsuba 3, src/bsdfs/null.cpp).
//
// The pass-through sample has flags kBSDFNull | kBSDFTransmission | kBSDFSpecular: a delta lobe
// (no next-event estimation through it, the emitter it reaches is counted with MIS weight 1) that
// the path integrator counts as a path segment like any other (Mitsuba 3, src/integrators/path.cpp:
// depth grows at every valid intersection), and its shadow rays stop at the surface whatever its
// opacity (Mitsuba 3's Scene::ray_test is a plain occlusion test). The volumetric integrators do
// not count the pass-through as a bounce and their shadow rays cross the surface with the weight
// 1 − opacity · (1 − the nested BSDF's own pass-through weight) (Mitsuba 3 mask.cpp,
// eval_null_transmission; `null`: 1).
//
// Two models, chosen by `convention` (core/mitsuba_convention.h; the upgrade pass gives a version
// 0.x file's masks "mitsuba0.6"; docs/scene_format.md, "Version-dependent defaults"):
//   * "mitsuba3" (default): opacity is a scalar (a float texture, clamped to [0, 1] when looked
//     up, Mitsuba 3 eval_opacity). The nested lobe is chosen with probability opacity and its
//     sample is returned unchanged: its f and pdf are the nested BSDF's, while pdf(wo, wi) is
//     opacity · pdf_nested. So MIS weighs an emitter reached by BSDF sampling with the nested pdf
//     and next-event estimation with opacity · pdf_nested, exactly as Mitsuba 3 does (the weights
//     then sum to more than 1 where 0 < opacity < 1; iris reproduces this to render as Mitsuba 3).
//   * "mitsuba0.6" (src/bsdfs/mask.cpp): opacity is a spectrum or texture, per channel
//     (wavelength); the nested lobe is chosen with probability p = mean opacity over the lanes
//     (0.6: its luminance; any p > 0 where opacity > 0 gives the same expectation) and the sample is
//     weighted consistently: f = opacity · f_nested, pdf = p · pdf_nested; the pass-through carries
//     (1 − opacity) / (1 − p).
// A constant opacity outside [0, 1] is refused (Mitsuba clamps silently); texture values are
// clamped as Mitsuba does.
#include <algorithm>

#include "core/error.h"
#include "core/registry.h"
#include "materials/material.h"
#include "materials/textures/texture_params.h"

namespace iris {
namespace {

constexpr uint32_t kNullLobe = kBSDFNull | kBSDFTransmission | kBSDFSpecular;

/// The pass-through lobe chosen with probability `prob`, carrying `transmission` (per lane):
/// wi = −wo, pdf = prob (a discrete probability), f·|cosθi| = transmission (bsdf.h convention).
std::optional<BSDFSample> passThrough(const vec3& wo, const SampledSpectrum& transmission, float prob) {
    const float c = std::abs(wo.z);
    if (!(c > 0) || !(prob > 0)) return std::nullopt;
    BSDFSample s;
    s.wi = -wo;
    s.pdf = prob;
    s.f = transmission / c;
    s.flags = kNullLobe;
    s.eta = 1.0f;
    return s;
}

class MaskBSDF final : public BSDF {
public:
    /// `opacity`: per lane in [0, 1]; `prob`: probability of the nested lobe; `mitsuba3`: return
    /// the nested sample unchanged (Mitsuba 3) instead of weighting it consistently (0.6).
    MaskBSDF(const BSDF* nested, const SampledSpectrum& opacity, float prob, bool mitsuba3)
        : nested_(nested), opacity_(opacity), prob_(prob), mitsuba3_(mitsuba3) {}

    SampledSpectrum eval(const vec3& wo, const vec3& wi, TransportMode mode) const override {
        if (!nested_) return SampledSpectrum(opacity_.size());
        return nested_->eval(wo, wi, mode) * opacity_;  // f = opacity · f_nested
    }
    float pdf(const vec3& wo, const vec3& wi, TransportMode mode) const override {
        return nested_ ? nested_->pdf(wo, wi, mode) * prob_ : 0.0f;  // the nested lobe's share
    }
    std::optional<BSDFSample> sample(const vec3& wo, float uc, const vec2& u, TransportMode mode) const override {
        if (uc < prob_) {  // nested lobe (Mitsuba: sample1 < opacity, then sample1 / opacity)
            if (!nested_) return std::nullopt;
            auto s = nested_->sample(wo, std::min(uc / prob_, 0x1.fffffep-1f), u, mode);
            if (!s) return std::nullopt;
            if (!mitsuba3_) {
                s->f *= opacity_;
                s->pdf *= prob_;
            }
            return s;
        }
        return passThrough(wo, 1.0f - opacity_, 1.0f - prob_);
    }
    uint32_t flags() const override { return (nested_ ? nested_->flags() : 0u) | kNullLobe; }
    std::optional<SampledSpectrum> nullTransmission(const vec3& wo) const override {
        const SampledSpectrum one(opacity_.size(), 1.0f);
        const SampledSpectrum nested = (nested_ ? nested_->nullTransmission(wo) : std::nullopt).value_or(SampledSpectrum(opacity_.size()));
        return one - opacity_ * (one - nested);  // Mitsuba 3 mask.cpp eval_null_transmission
    }
    // Polarized: the nested BSDF's matrices times opacity; the pass-through is an absorber (an
    // unchanged Stokes vector, whose basis stokesBasis(wo) is the same on both sides).
    MuellerSpectrum evalMueller(const vec3& wo, const vec3& wi, TransportMode mode) const override {
        if (!nested_) return MuellerSpectrum::depolarizer(SampledSpectrum(opacity_.size()));
        return nested_->evalMueller(wo, wi, mode) * opacity_;
    }
    std::optional<PolarizedBSDFSample> sampleMueller(const vec3& wo, float uc, const vec2& u, TransportMode mode) const override {
        if (uc < prob_) {
            if (!nested_) return std::nullopt;
            auto s = nested_->sampleMueller(wo, std::min(uc / prob_, 0x1.fffffep-1f), u, mode);
            if (s && !mitsuba3_) {
                s->s.f *= opacity_;
                s->s.pdf *= prob_;
                s->M *= opacity_;
            }
            return s;
        }
        const std::optional<BSDFSample> s = passThrough(wo, 1.0f - opacity_, 1.0f - prob_);
        if (!s) return std::nullopt;
        return PolarizedBSDFSample{*s, MuellerSpectrum::absorber(s->f)};
    }
    std::optional<MuellerSpectrum> nullTransmissionMueller(const vec3& wo) const override {
        MuellerSpectrum M = MuellerSpectrum::absorber(1.0f - opacity_);  // 1 − opacity (1 − nested)
        if (const auto nested = nested_ ? nested_->nullTransmissionMueller(wo) : std::nullopt) M += *nested * opacity_;
        return M;
    }

private:
    const BSDF* nested_;
    SampledSpectrum opacity_;
    float prob_;
    bool mitsuba3_;
};

class NullBSDF final : public BSDF {
public:
    explicit NullBSDF(int n) : n_(n) {}
    SampledSpectrum eval(const vec3&, const vec3&, TransportMode) const override { return SampledSpectrum(n_); }
    float pdf(const vec3&, const vec3&, TransportMode) const override { return 0.0f; }
    std::optional<BSDFSample> sample(const vec3& wo, float, const vec2&, TransportMode) const override {
        return passThrough(wo, SampledSpectrum(n_, 1.0f), 1.0f);
    }
    uint32_t flags() const override { return kNullLobe; }
    std::optional<SampledSpectrum> nullTransmission(const vec3&) const override { return SampledSpectrum(n_, 1.0f); }
    std::optional<PolarizedBSDFSample> sampleMueller(const vec3& wo, float uc, const vec2& u, TransportMode mode) const override {
        const std::optional<BSDFSample> s = sample(wo, uc, u, mode);
        if (!s) return std::nullopt;
        return PolarizedBSDFSample{*s, MuellerSpectrum::absorber(s->f)};  // the Stokes vector passes unchanged
    }

private:
    int n_;
};

class MaskMaterial final : public Material {
public:
    MaskMaterial(FloatTexturePtr opacity, SpectrumTexturePtr spectralOpacity, std::shared_ptr<Material> nested)
        : opacity_(std::move(opacity)), spectralOpacity_(std::move(spectralOpacity)), nested_(std::move(nested)) {}

    const BSDF* getBSDF(const ShadingPoint& sp, SampledWavelengths& wl, Arena& arena) const override {
        const BSDF* nested = nested_->getBSDF(sp, wl, arena);
        if (opacity_) {  // Mitsuba 3: one scalar opacity, clamped to [0, 1]
            const float o = std::clamp(opacity_->eval(sp.tex), 0.0f, 1.0f);
            return arena.make<MaskBSDF>(nested, SampledSpectrum(wl.size(), o), o, true);
        }
        SampledSpectrum o = spectralOpacity_->eval(sp.tex, wl);  // Mitsuba 0.6: per channel
        float sum = 0.0f;
        for (int k = 0; k < o.size(); ++k) {
            o[k] = std::clamp(o[k], 0.0f, 1.0f);
            sum += o[k];
        }
        return arena.make<MaskBSDF>(nested, o, std::clamp(sum / float(o.size()), 0.0f, 1.0f), false);
    }
    Frame shadingFrame(const ShadingPoint& sp) const override { return nested_->shadingFrame(sp); }
    bool transmitsShadowRays() const override { return true; }

private:
    FloatTexturePtr opacity_;
    SpectrumTexturePtr spectralOpacity_;
    std::shared_ptr<Material> nested_;
};

class NullMaterial final : public Material {
public:
    const BSDF* getBSDF(const ShadingPoint&, SampledWavelengths& wl, Arena& arena) const override {
        return arena.make<NullBSDF>(wl.size());
    }
    bool transmitsShadowRays() const override { return true; }
};

std::shared_ptr<Material> nestedMaterial(const Properties& child) {
    return cachedObject<Material>(child, [&] { return MaterialRegistry::instance().create(child); });
}

std::shared_ptr<Material> createMask(const Properties& p) {
    // The nested bsdf: an unnamed child, or a bsdf under any name but `opacity` (Mitsuba 3 takes
    // every nested BSDF object and refuses a second one).
    std::vector<PropertiesPtr> nested;
    for (const PropertiesPtr& c : p.children()) {
        if (c->tag() != "bsdf") failAt(c->location(), "mask: nested object must be a bsdf, not a ", c->tag());
        nested.push_back(c);
    }
    for (const std::string& name : p.names()) {
        if (name == "opacity") continue;
        const PropertiesPtr* obj = p.peekObject(name);
        if (obj && (*obj)->tag() == "bsdf") nested.push_back(p.getObject(name));
    }
    if (nested.empty()) failAt(p.location(), "mask: no nested bsdf (Mitsuba: \"Child BSDF not specified\")");
    if (nested.size() > 1)
        failAt(nested[1]->location(), "mask: more than one nested bsdf (Mitsuba: \"Cannot specify more than one child BSDF\")");

    FloatTexturePtr opacity;
    SpectrumTexturePtr spectral;
    if (getConvention(p) == MitsubaConvention::Mitsuba06)
        spectral = getSpectrumTexture(p, "opacity", SpectrumKind::Reflectance, 0.5f);
    else
        opacity = getFloatTexture(p, "opacity", 0.5f);
    // A constant opacity must be an opacity (Mitsuba clamps it silently; a texture's texels are
    // clamped when looked up, as in Mitsuba).
    if (opacity && opacity->isConstant()) {
        const float o = opacity->eval(TextureQuery{});
        if (!(o >= 0.0f && o <= 1.0f)) failAt(p.locationOf("opacity"), "mask: opacity ", o, " is outside [0, 1]");
    }
    if (spectral && spectral->isConstant()) {
        // Checked as RGB (the triple) and at 32 wavelengths over [360, 830] nm.
        for (const SampledWavelengths& wl : parameterCheckWavelengths()) {
            const SampledSpectrum o = spectral->eval(TextureQuery{}, wl);
            for (int k = 0; k < o.size(); ++k)
                if (!(o[k] >= 0.0f && o[k] <= 1.0f + 1e-4f))
                    failAt(p.locationOf("opacity"), "mask: opacity ", o[k], " at ", wl.lambda(k), " nm is outside [0, 1]");
        }
    }
    return std::make_shared<MaskMaterial>(opacity, spectral, nestedMaterial(*nested[0]));
}

std::shared_ptr<Material> createNull(const Properties&) { return std::make_shared<NullMaterial>(); }

}  // namespace

IRIS_REGISTER(MaterialRegistry, "mask", createMask);
IRIS_REGISTER(MaterialRegistry, "null", createNull);

}  // namespace iris
