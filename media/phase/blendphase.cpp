// Linear blend of two phase functions (Mitsuba 3 `blendphase`, src/phase/blendphase.cpp):
//   p = (1 − w) p₀ + w p₁,   pdf = (1 − w) pdf₀ + w pdf₁,
// with `weight` w (default 0.5) a float or a 1-channel <volume> looked up at the scattering point
// (values clamped to [0, 1] as Mitsuba 3 does; a constant outside [0, 1] is refused), and exactly
// two nested <phase>s: w = 0 is the first, w = 1 the second, in Mitsuba's order — unnamed ones in
// document order, then named ones in the alphanumeric order of their names.
//
// Sampling picks p₁ with probability w (Mitsuba 3: when the 1D sample is ≤ w; iris reuses the
// first coordinate of the 2D sample, rescaled) and samples it. The sample carries the blend's p
// and pdf at the sampled direction, so that MIS with next-event estimation is consistent; Mitsuba 3
// returns the chosen component's own pdf (the same path weight for phase functions sampled
// exactly, other MIS weights).
#include <algorithm>
#include <vector>

#include "core/error.h"
#include "media/phase/phase_function.h"
#include "media/volumes/volume.h"

namespace iris {
namespace {

class BlendPhase final : public PhaseFunction {
public:
    BlendPhase(FloatVolume weight, PhaseFunctionPtr first, PhaseFunctionPtr second)
        : weight_(std::move(weight)), phase_{std::move(first), std::move(second)} {}

    float eval(const vec3& x, const vec3& wo, const vec3& wi) const override {
        const float w = weightAt(x);
        return (1.0f - w) * phase_[0]->eval(x, wo, wi) + w * phase_[1]->eval(x, wo, wi);
    }
    float pdf(const vec3& x, const vec3& wo, const vec3& wi) const override {
        const float w = weightAt(x);
        return (1.0f - w) * phase_[0]->pdf(x, wo, wi) + w * phase_[1]->pdf(x, wo, wi);
    }
    std::optional<PhaseSample> sample(const vec3& x, const vec3& wo, const vec2& u) const override {
        const float w = weightAt(x);
        const bool second = u.x < w;
        const float ux = second ? u.x / w : (u.x - w) / (1.0f - w);
        const auto s = phase_[second ? 1 : 0]->sample(x, wo, vec2(std::min(ux, 0x1.fffffep-1f), u.y));
        if (!s) return std::nullopt;
        return PhaseSample{s->wi, eval(x, wo, s->wi), pdf(x, wo, s->wi)};
    }
    /// Polarized: the blend of the nested matrices, (1 − w) M₀ + w M₁.
    MuellerSpectrum evalMueller(const vec3& x, const vec3& wo, const vec3& wi, int n) const override {
        const float w = weightAt(x);
        MuellerSpectrum M = phase_[0]->evalMueller(x, wo, wi, n) * (1.0f - w);
        M += phase_[1]->evalMueller(x, wo, wi, n) * w;
        return M;
    }

private:
    float weightAt(const vec3& x) const { return std::clamp(weight_.eval(x), 0.0f, 1.0f); }

    FloatVolume weight_;
    PhaseFunctionPtr phase_[2];
};

/// The nested phase functions in Mitsuba's order (see the file comment).
std::vector<PhaseFunctionPtr> nestedPhases(const Properties& p) {
    std::vector<PropertiesPtr> nested;
    for (const PropertiesPtr& c : p.children()) {
        if (c->tag() != "phase") failAt(c->location(), "blendphase: unexpected <", c->tag(), "> (expected two <phase>s)");
        nested.push_back(c);
    }
    for (const std::string& name : p.names()) {
        const PropertiesPtr* obj = p.peekObject(name);
        if (name != "weight" && obj && (*obj)->tag() == "phase") nested.push_back(p.getObject(name));
    }
    std::vector<PhaseFunctionPtr> out;
    for (const PropertiesPtr& c : nested) out.push_back(PhaseFunctionRegistry::instance().create(*c));
    return out;
}

std::shared_ptr<PhaseFunction> createBlend(const Properties& p) {
    FloatVolume weight = getFloatVolume(p, "weight", 0.5f);
    if (!weight.volume && !(weight.constant >= 0.0f && weight.constant <= 1.0f))
        failAt(p.locationOf("weight"), "blendphase: weight = ", weight.constant, " must lie in [0, 1]");
    std::vector<PhaseFunctionPtr> phases = nestedPhases(p);
    if (phases.size() != 2) failAt(p.location(), "blendphase: needs exactly two nested <phase>s, got ", phases.size());
    return std::make_shared<BlendPhase>(std::move(weight), std::move(phases[0]), std::move(phases[1]));
}

}  // namespace

IRIS_REGISTER(PhaseFunctionRegistry, "blendphase", createBlend);

}  // namespace iris
