// Directional light (Mitsuba "directional"): irradiance E on surfaces facing the direction;
// the light travels along `direction` (or +z of to_world).
#include "render/lights/light_emission.h"
#include "core/registry.h"
#include "spectral/spectrum.h"
#include "spectral/spectrum_params.h"

namespace iris {
namespace {

class DirectionalLight final : public Light {
public:
    DirectionalLight(const vec3& direction, SpectrumPtr irradiance)
        : dir_(glm::normalize(direction)), irradiance_(std::move(irradiance)) {}
    Type type() const override { return Type::DeltaDirection; }
    void preprocess(const SceneBounds& b) override { sceneRadius_ = b.radius; }

    std::optional<LightSample> sampleLi(const vec3& p, const vec2&, const SampledWavelengths& wl) const override {
        LightSample ls;
        ls.wi = -dir_;
        ls.pdf = 1.0f;
        ls.infinite = true;
        ls.pLight = p + ls.wi * (2.0f * sceneRadius_);
        ls.L = irradiance_->sample(wl);
        return ls;
    }

    /// A ray along the light's direction from a disk that covers the scene, carrying the
    /// irradiance (pbrt-v4 §12.4 DistantLight::SampleLe: pdfPos = 1/(πR²), the direction a delta).
    std::optional<LightEmission> sampleLe(const vec2& uPos, const vec2&, const SampledWavelengths& wl,
                                          const SceneBounds& bounds) const override {
        LightEmission e;
        e.ray = Ray(emissionDiskOrigin(bounds, -dir_, uPos), dir_);
        e.L = irradiance_->sample(wl);
        e.pdfPos = emissionDiskPdf(bounds);
        e.pdfDir = 1.0f;
        return e;
    }
    /// No ray of another technique can reach a delta direction (pbrt-v4 DistantLight::PDF_Le).
    vec2 pdfLe(const vec3&, const vec3&, const vec3&, const SceneBounds&) const override { return vec2(0.0f); }

private:
    vec3 dir_;
    SpectrumPtr irradiance_;
    float sceneRadius_ = 1.0f;
};

std::shared_ptr<Light> createDirectional(const Properties& p) {
    vec3 d = p.has("direction") ? p.getVector("direction") : vec3(0, 0, 1);
    d = transformVector(p.getTransform("to_world"), d);
    if (!(glm::length(d) > 0) || !isFinite(d)) failAt(p.location(), "directional light needs a non-zero direction");
    return std::make_shared<DirectionalLight>(d, getSpectrum(p, "irradiance", SpectrumKind::Illuminant, 1.0f));
}

}  // namespace

IRIS_REGISTER(LightRegistry, "directional", createDirectional);

}  // namespace iris
