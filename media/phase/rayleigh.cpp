// Rayleigh phase function (Mitsuba 3 `rayleigh`, no parameters; Chandrasekhar 1960, "Radiative
// Transfer", unpolarised): p(θ) = 3 (1 + cos²θ) / (16π), cos θ = −wo·wi (phase_function.h).
// Its angular shape does not depend on wavelength (the λ⁻⁴ law belongs to σ_s, i.e. the medium).
// Sampled exactly: the CDF of μ = cos θ is (μ³ + 3μ + 4)/8; setting it to ξ gives the depressed
// cubic μ³ + 3μ + (4 − 8ξ) = 0 with the single real root (Cardano)
//   μ = A − 1/A,   A = ∛(z + √(z² + 1)),   z = 4ξ − 2
// (Frisvad 2011, "Importance sampling the Rayleigh phase function", JOSA A 28(12), eq. 8).
#include "media/phase/phase_function.h"
#include "media/phase/phase_sampling.h"
#include "spectral/stokes_basis.h"

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
    /// Polarized: the Rayleigh scattering matrix (Chandrasekhar 1960, "Radiative Transfer", §I.17;
    /// Hansen & Travis 1974, "Light scattering in planetary atmospheres", eq. 2.15) with the basis
    /// vector normal to the scattering plane on both sides:
    ///   3/(16π) [[1 + c², 1 − c², 0, 0], [1 − c², 1 + c², 0, 0], [0, 0, 2c, 0], [0, 0, 0, 2c]],
    /// c = cos θ: the dipole's amplitudes 1 (normal to the plane) and c (in it), in the interface
    /// layout of mueller::interfaceMueller (so backscattering acts like a mirror at normal
    /// incidence). Unpolarized light scattered at 90° leaves fully polarized normal to the plane.
    /// (Mitsuba 3's rayleigh is unpolarized in its polarized variants.)
    MuellerSpectrum evalMueller(const vec3&, const vec3& wo, const vec3& wi, int n) const override {
        const float c = -glm::dot(wo, wi), k = 3.0f / (16.0f * kPi);
        const MuellerSpectrum M = mueller::interfaceMueller(SampledSpectrum(n, k * (1 + c * c)), SampledSpectrum(n, k * (1 - c * c)),
                                                            SampledSpectrum(n, 2 * k * c), SampledSpectrum(n));
        const vec3 normal = glm::cross(-wi, wo);
        const float l2 = glm::dot(normal, normal);
        const vec3 s = l2 > 1e-12f ? normal / std::sqrt(l2) : stokesBasis(wo);  // forward or backward: any normal axis
        return toImplicitBases(M, -wi, s, wo, s);
    }
};

std::shared_ptr<PhaseFunction> createRayleigh(const Properties&) { return std::make_shared<RayleighPhase>(); }

}  // namespace

IRIS_REGISTER(PhaseFunctionRegistry, "rayleigh", createRayleigh);

}  // namespace iris
