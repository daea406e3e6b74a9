// Rayleigh phase function (Mitsuba 3 `rayleigh`, no parameters; Chandrasekhar 1960, "Radiative
// Transfer", unpolarised): p(θ) = 3 (1 + cos²θ) / (16π), cos θ = −wo·wi (phase_function.h).
// Its angular shape does not depend on wavelength (the λ⁻⁴ law belongs to σ_s, i.e. the medium).
// Sampled exactly: the CDF of μ = cos θ is (μ³ + 3μ + 4)/8; setting it to ξ gives the depressed
// cubic μ³ + 3μ + (4 − 8ξ) = 0 with the single real root (Cardano)
//   μ = A − 1/A,   A = ∛(z + √(z² + 1)),   z = 4ξ − 2
// (Frisvad 2011, "Importance sampling the Rayleigh phase function", JOSA A 28(12), eq. 8).
#include "media/phase/phase_function.h"
#include "media/phase/phase_sampling.h"

namespace iris {
namespace {

float rayleigh(float cosTheta) { return 3.0f / (16.0f * kPi) * (1.0f + cosTheta * cosTheta); }

class RayleighPhase final : public PhaseFunction {
public:
    float eval(const vec3&, const vec3& wo, const vec3& wi) const override { return rayleigh(-glm::dot(wo, wi)); }
    float pdf(const vec3&, const vec3& wo, const vec3& wi) const override { return rayleigh(-glm::dot(wo, wi)); }
    std::optional<PhaseSample> sample(const vec3&, const vec3& wo, const vec2& u) const override {
        const float z = 4.0f * u.x - 2.0f;
        const float a = std::cbrt(z + std::sqrt(z * z + 1.0f));
        const vec3 wi = directionWithScatteringCosine(wo, a - 1.0f / a, u.y);
        const float p = rayleigh(-glm::dot(wo, wi));
        return PhaseSample{wi, p, p};
    }
};

std::shared_ptr<PhaseFunction> createRayleigh(const Properties&) { return std::make_shared<RayleighPhase>(); }

}  // namespace

IRIS_REGISTER(PhaseFunctionRegistry, "rayleigh", createRayleigh);

}  // namespace iris
