// Constant environment (Mitsuba "constant"): uniform radiance from every direction; sampled
// uniformly on the sphere.
#include "render/lights/light.h"
#include "core/registry.h"
#include "core/sampling.h"
#include "spectral/spectrum.h"
#include "spectral/spectrum_params.h"

namespace iris {
namespace {

class ConstantLight final : public Light {
public:
    explicit ConstantLight(SpectrumPtr radiance) : radiance_(std::move(radiance)) {}
    Type type() const override { return Type::Infinite; }

    std::optional<LightSample> sampleLi(const vec3& p, const vec2& u, const SampledWavelengths& wl) const override {
        LightSample ls;
        ls.wi = sampleUniformSphere(u);
        ls.pdf = uniformSpherePdf();
        ls.infinite = true;
        ls.L = radiance_->sample(wl);
        return ls;
    }
    float pdfLi(const vec3&, const vec3&, const SurfaceInteraction*) const override { return uniformSpherePdf(); }
    SampledSpectrum Le(const TextureQuery&, const vec3&, const vec3&, const SampledWavelengths& wl) const override {
        return radiance_->sample(wl);
    }

private:
    SpectrumPtr radiance_;
};

std::shared_ptr<Light> createConstant(const Properties& p) {
    return std::make_shared<ConstantLight>(getSpectrum(p, "radiance", SpectrumKind::Illuminant, 1.0f));
}

}  // namespace

IRIS_REGISTER(LightRegistry, "constant", createConstant);

}  // namespace iris
