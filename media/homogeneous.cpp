// Homogeneous participating medium (Mitsuba 3 `homogeneous`, src/media/homogeneous.cpp):
// `sigma_t` (float or spectrum, 1/scene units, default 1), `albedo` (float or spectrum in [0, 1],
// default 0.75), `scale` (default 1, multiplies σ_t), `sample_emitters`, a nested `<phase>`.
// Mitsuba 0.6's form, `sigma_a` and `sigma_s` (sigmaA, sigmaS), is accepted instead of
// sigma_t/albedo: σ_t = σ_a + σ_s, albedo = σ_s/σ_t. Spectral values are per wavelength: a
// chromatic medium (σ_t varying with λ) is what hero-wavelength sampling with spectral MIS is for
// (integrators/volpath.cpp). σ_t is constant in space, so the majorant is σ_t itself and there are
// no null collisions: free-flight sampling is exact for the sampling lane.
#include "core/error.h"
#include "media/medium.h"
#include "spectral/spectrum_params.h"

namespace iris {
namespace {

/// Either (σ_t, albedo) (Mitsuba 3) or (σ_a, σ_s) (Mitsuba 0.6) as given; σ_t = scale·first,
/// σ_s = σ_t·albedo, or σ_t = scale·(σ_a + σ_s), σ_s = scale·σ_s.
class HomogeneousMedium final : public Medium {
public:
    HomogeneousMedium(const MediumCommon& c, SpectrumPtr a, SpectrumPtr b, bool absorptionForm, float scale)
        : Medium(c.phase, c.sampleEmitters, c.emission), a_(std::move(a)), b_(std::move(b)), absorptionForm_(absorptionForm), scale_(scale) {}

    MediumCoefficients coefficients(const vec3&, const SampledWavelengths& wl) const override {
        const SampledSpectrum a = a_->sample(wl), b = b_->sample(wl);
        if (absorptionForm_) return {b * scale_, (a + b) * scale_};
        const SampledSpectrum st = a * scale_;
        return {st * b, st};
    }
    MajorantIterator* majorants(const Ray&, float tMax, const SampledWavelengths& wl, Arena& arena) const override {
        return arena.make<ConstantMajorantIterator>(0.0f, tMax, coefficients(vec3(0.0f), wl).sigmaT);
    }

private:
    SpectrumPtr a_, b_;
    bool absorptionForm_;
    float scale_;
};

std::shared_ptr<Medium> createHomogeneous(const Properties& p) {
    const MediumCommon common = readMediumCommon(p);
    const float scale = p.getFloat("scale", 1.0f);
    if (!(scale >= 0.0f) || !std::isfinite(scale)) failAt(p.locationOf("scale"), "<medium type=\"homogeneous\">: scale = ", scale, " must be >= 0");
    constexpr float kHuge = 1e30f;
    if (p.has("sigma_a") || p.has("sigma_s")) {  // Mitsuba 0.6's parameters
        for (const char* other : {"sigma_t", "albedo"})
            if (p.has(other)) failAt(p.locationOf(other), "<medium type=\"homogeneous\">: give either sigma_a and sigma_s or sigma_t and albedo, not both");
        SpectrumPtr sa = getSpectrum(p, "sigma_a", SpectrumKind::Unbounded, 0.0f);
        SpectrumPtr ss = getSpectrum(p, "sigma_s", SpectrumKind::Unbounded, 0.0f);
        checkMediumSpectrum(p, "sigma_a", *sa, 0.0f, kHuge);
        checkMediumSpectrum(p, "sigma_s", *ss, 0.0f, kHuge);
        return std::make_shared<HomogeneousMedium>(common, sa, ss, true, scale);
    }
    SpectrumPtr st = getSpectrum(p, "sigma_t", SpectrumKind::Unbounded, 1.0f);
    SpectrumPtr albedo = getSpectrum(p, "albedo", SpectrumKind::Reflectance, 0.75f);
    checkMediumSpectrum(p, "sigma_t", *st, 0.0f, kHuge);
    checkMediumSpectrum(p, "albedo", *albedo, 0.0f, 1.0f);
    return std::make_shared<HomogeneousMedium>(common, st, albedo, false, scale);
}

}  // namespace

IRIS_REGISTER(MediumRegistry, "homogeneous", createHomogeneous);

}  // namespace iris
