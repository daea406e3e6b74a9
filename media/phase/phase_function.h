// The phase function interface of participating media (Mitsuba 3 `<phase>` plugins, pbrt-v4
// §11.3). Directions are world-space unit vectors pointing away from the scattering point, as for
// BSDFs: wo towards the previous path vertex (−ray direction), wi towards the next one (or the
// light). The scattering angle θ is the angle between the incident propagation direction −wi and
// the outgoing one wo, cos θ = −wo·wi; forward scattering (the ray goes on undeflected) is wi = −wo.
// p(wo, wi) is a density per unit solid angle over the sphere of wi (∫ p dωi = 1). The rotationally
// symmetric ones (a function of cos θ alone) are symmetric, p(wo, wi) = p(wi, wo); a microflake
// phase function (`sggx`) is reciprocal only with its projected area, σ(wo) p(wo, wi) =
// σ(wi) p(wi, wo). Every phase function here is sampled exactly (sample().weight = 1 up to
// rounding); the interface still carries the weight p/pdf so that one that is not can be added.
// Every method takes the world-space scattering point x: phase functions whose parameters are
// volumes (`sggx`'s S, `blendphase`'s weight; Mitsuba 3 passes the MediumInteraction) look them up
// there; the others ignore it.
// Each type registers a factory in PhaseFunctionRegistry under its scene-file name.
#pragma once

#include <memory>
#include <optional>

#include "core/math.h"
#include "core/registry.h"
#include "spectral/mueller.h"

namespace iris {

struct PhaseSample {
    vec3 wi{0.0f};      // sampled direction (world, unit)
    float p = 0.0f;     // phase function value p(wo, wi)
    float pdf = 0.0f;   // solid-angle density of the sample
    float weight() const { return pdf > 0 ? p / pdf : 0.0f; }
};

class PhaseFunction {
public:
    virtual ~PhaseFunction() = default;
    /// p(wo, wi) at the world point x, 1/sr.
    virtual float eval(const vec3& x, const vec3& wo, const vec3& wi) const = 0;
    /// wi ~ pdf from the 2D sample u in [0, 1)², at the world point x.
    virtual std::optional<PhaseSample> sample(const vec3& x, const vec3& wo, const vec2& u) const = 0;
    /// Solid-angle density of sample() at the world point x.
    virtual float pdf(const vec3& x, const vec3& wo, const vec3& wi) const = 0;
    /// Polarized mode (docs/polarization.md): p(wo, wi) as a Mueller matrix at n wavelengths, from
    /// the Stokes basis of the light arriving, stokesBasis(−wi), to that of the light leaving,
    /// stokesBasis(wo) (world space, spectral/stokes_basis.h). The default depolarizes (Mitsuba 3's
    /// phase functions are unpolarized); Rayleigh scattering polarizes.
    virtual MuellerSpectrum evalMueller(const vec3& x, const vec3& wo, const vec3& wi, int n) const {
        return MuellerSpectrum::depolarizer(SampledSpectrum(n, eval(x, wo, wi)));
    }
};

using PhaseFunctionPtr = std::shared_ptr<const PhaseFunction>;
/// Every phase function type, by its scene-file name (`<phase type="...">`).
using PhaseFunctionRegistry = Registry<PhaseFunction>;

}  // namespace iris
