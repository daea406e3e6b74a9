// Henyey–Greenstein phase function (Henyey & Greenstein 1941, "Diffuse radiation in the galaxy",
// ApJ 93; Mitsuba 3 `hg`, parameter `g` in (−1, 1), default 0.8 as in Mitsuba 3 src/phase/hg.cpp):
//   p(θ) = (1 − g²) / (4π (1 + g² − 2g cos θ)^{3/2}),   cos θ = −wo·wi (phase_function.h),
// so g > 0 scatters forward (wi near −wo) and g is the mean cosine of the scattering angle.
// Sampled exactly by inverting its CDF (pbrt-v4 §11.3.1, eq. 11.12):
//   cos θ = (1 + g² − ((1 − g²) / (1 − g + 2gξ))²) / (2g),   and cos θ = 1 − 2ξ as g → 0.
#include "core/error.h"
#include "media/phase/phase_function.h"
#include "media/phase/phase_sampling.h"

namespace iris {
namespace {

class HenyeyGreenstein final : public PhaseFunction {
public:
    explicit HenyeyGreenstein(float g) : g_(g) {}

    float eval(const vec3&, const vec3& wo, const vec3& wi) const override { return value(-glm::dot(wo, wi)); }
    float pdf(const vec3&, const vec3& wo, const vec3& wi) const override { return value(-glm::dot(wo, wi)); }
    std::optional<PhaseSample> sample(const vec3&, const vec3& wo, const vec2& u) const override {
        const vec3 wi = directionWithScatteringCosine(wo, sampleCosine(u.x), u.y);
        const float p = value(-glm::dot(wo, wi));
        return PhaseSample{wi, p, p};
    }

private:
    float value(float cosTheta) const {
        const float denom = 1.0f + g_ * g_ - 2.0f * g_ * cosTheta;
        return kInv4Pi * (1.0f - g_ * g_) / (denom * std::sqrt(std::max(denom, 1e-30f)));
    }
    float sampleCosine(float xi) const {
        if (std::abs(g_) < 1e-3f) return 1.0f - 2.0f * xi;
        const float s = (1.0f - g_ * g_) / (1.0f - g_ + 2.0f * g_ * xi);
        return (1.0f + g_ * g_ - s * s) / (2.0f * g_);
    }
    float g_;
};

std::shared_ptr<PhaseFunction> createHG(const Properties& p) {
    const float g = p.getFloat("g", 0.8f);
    if (!(g > -1.0f && g < 1.0f)) failAt(p.locationOf("g"), "hg: the asymmetry parameter g = ", g, " must lie in (-1, 1)");
    return std::make_shared<HenyeyGreenstein>(g);
}

}  // namespace

IRIS_REGISTER(PhaseFunctionRegistry, "hg", createHG);

}  // namespace iris
