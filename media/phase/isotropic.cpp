// Isotropic phase function (Mitsuba 3 `isotropic`, no parameters): p = 1/(4π) (pbrt-v4 §11.3).
#include "core/sampling.h"
#include "media/phase/phase_function.h"

namespace iris {
namespace {

class IsotropicPhase final : public PhaseFunction {
public:
    float eval(const vec3&, const vec3&, const vec3&) const override { return kInv4Pi; }
    float pdf(const vec3&, const vec3&, const vec3&) const override { return kInv4Pi; }
    std::optional<PhaseSample> sample(const vec3&, const vec3&, const vec2& u) const override {
        return PhaseSample{sampleUniformSphere(u), kInv4Pi, kInv4Pi};
    }
};

std::shared_ptr<PhaseFunction> createIsotropic(const Properties&) { return std::make_shared<IsotropicPhase>(); }

}  // namespace

IRIS_REGISTER(PhaseFunctionRegistry, "isotropic", createIsotropic);

}  // namespace iris
