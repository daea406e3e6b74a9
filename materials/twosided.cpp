// Two-sided adapter (Mitsuba 3 plugin "twosided"): one-sided BSDFs are zero when wo.z <= 0;
// this wrapper evaluates the front BSDF for wo.z > 0 and, for wo.z < 0, the back BSDF (the same
// one unless a second is given) with both directions mirrored to the upper side (z → −z).
// Parameters: one or two nested <bsdf> children (unnamed, or under any name; first = front).
#include "core/registry.h"
#include "materials/material.h"
#include "materials/mueller_frames.h"

namespace iris {
namespace {

inline vec3 flipZ(const vec3& w) { return vec3(w.x, w.y, -w.z); }
/// The back BSDF's local frame in this one's coordinates: z → −z (an improper map).
const Frame kFlippedFrame(vec3(1, 0, 0), vec3(0, 1, 0), vec3(0, 0, -1));

class TwoSidedBSDF final : public BSDF {
public:
    TwoSidedBSDF(const BSDF* front, const BSDF* back, int n) : front_(front), back_(back), n_(n) {}

    SampledSpectrum eval(const vec3& wo, const vec3& wi, TransportMode mode) const override {
        if (wo.z > 0) return front_ ? front_->eval(wo, wi, mode) : SampledSpectrum(n_);
        if (wo.z < 0) return back_ ? back_->eval(flipZ(wo), flipZ(wi), mode) : SampledSpectrum(n_);
        return SampledSpectrum(n_);
    }
    float pdf(const vec3& wo, const vec3& wi, TransportMode mode) const override {
        if (wo.z > 0) return front_ ? front_->pdf(wo, wi, mode) : 0.0f;
        if (wo.z < 0) return back_ ? back_->pdf(flipZ(wo), flipZ(wi), mode) : 0.0f;
        return 0.0f;
    }
    std::optional<BSDFSample> sample(const vec3& wo, float uc, const vec2& u, TransportMode mode) const override {
        if (wo.z > 0) return front_ ? front_->sample(wo, uc, u, mode) : std::nullopt;
        if (wo.z < 0 && back_) {
            auto s = back_->sample(flipZ(wo), uc, u, mode);
            if (s) s->wi = flipZ(s->wi);
            return s;
        }
        return std::nullopt;
    }
    uint32_t flags() const override { return (front_ ? front_->flags() : 0u) | (back_ ? back_->flags() : 0u); }
    /// Polarized: the back BSDF's matrix, computed in the mirrored frame, is mapped back with the
    /// mirror's change of handedness (materials/mueller_frames.h fromNestedFrame; Mitsuba 3's
    /// twosided hands it on without, docs/polarization.md).
    MuellerSpectrum evalMueller(const vec3& wo, const vec3& wi, TransportMode mode) const override {
        if (wo.z > 0 && front_) return front_->evalMueller(wo, wi, mode);
        if (wo.z < 0 && back_) return fromNestedFrame(back_->evalMueller(flipZ(wo), flipZ(wi), mode), kFlippedFrame, true, wi, wo);
        return MuellerSpectrum::depolarizer(SampledSpectrum(n_));
    }
    std::optional<PolarizedBSDFSample> sampleMueller(const vec3& wo, float uc, const vec2& u, TransportMode mode) const override {
        if (wo.z > 0) return front_ ? front_->sampleMueller(wo, uc, u, mode) : std::nullopt;
        if (!(wo.z < 0 && back_)) return std::nullopt;
        auto s = back_->sampleMueller(flipZ(wo), uc, u, mode);
        if (!s) return std::nullopt;
        s->s.wi = flipZ(s->s.wi);
        s->M = fromNestedFrame(s->M, kFlippedFrame, true, s->s.wi, wo);
        return s;
    }

private:
    const BSDF* front_;
    const BSDF* back_;
    int n_;
};

class TwoSidedMaterial final : public Material {
public:
    TwoSidedMaterial(std::shared_ptr<Material> front, std::shared_ptr<Material> back)
        : front_(std::move(front)), back_(std::move(back)) {}
    const BSDF* getBSDF(const ShadingPoint& sp, SampledWavelengths& wl, Arena& arena) const override {
        const BSDF* f = front_->getBSDF(sp, wl, arena);
        const BSDF* b = back_ == front_ ? f : back_->getBSDF(sp, wl, arena);
        if (!f && !b) return nullptr;
        return arena.make<TwoSidedBSDF>(f, b, wl.size());
    }
    Frame shadingFrame(const ShadingPoint& sp) const override { return front_->shadingFrame(sp); }
    bool perturbsShading() const override { return front_->perturbsShading() || back_->perturbsShading(); }

private:
    std::shared_ptr<Material> front_, back_;
};

std::shared_ptr<Material> createTwoSided(const Properties& p) {
    std::vector<PropertiesPtr> nested(p.children().begin(), p.children().end());
    for (const std::string& name : p.names()) nested.push_back(p.getObject(name));
    if (nested.empty() || nested.size() > 2)
        failAt(p.location(), "twosided: expected one or two nested bsdfs, got ", nested.size());
    std::vector<std::shared_ptr<Material>> mats;
    for (const PropertiesPtr& child : nested) {
        if (child->tag() != "bsdf") failAt(child->location(), "twosided: nested object must be a bsdf, not a ", child->tag());
        mats.push_back(cachedObject<Material>(*child, [&] { return MaterialRegistry::instance().create(*child); }));
    }
    return std::make_shared<TwoSidedMaterial>(mats[0], mats.size() > 1 ? mats[1] : mats[0]);
}

}  // namespace

IRIS_REGISTER(MaterialRegistry, "twosided", createTwoSided);

}  // namespace iris
