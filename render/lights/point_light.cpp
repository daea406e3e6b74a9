// Point and spot lights (Mitsuba "point", "spot"). Radiant intensity I (per steradian):
// L arriving at distance d is I/d². Spot: smooth falloff between beam_width and cutoff_angle
// (pbrt-v4 §12.2.1 smoothstep falloff).
#include "render/lights/light.h"
#include "core/registry.h"
#include "spectral/spectrum.h"
#include "spectral/spectrum_params.h"

namespace iris {
namespace {

class SpotLight final : public Light {
public:
    SpotLight(const mat4& toWorld, SpectrumPtr intensity, float cosCutoff, float cosBeam)
        : position_(transformPoint(toWorld, vec3(0.0f))),
          axis_(glm::normalize(transformVector(toWorld, vec3(0, 0, 1)))),
          intensity_(std::move(intensity)), cosCutoff_(cosCutoff), cosBeam_(cosBeam) {}

    Type type() const override { return Type::DeltaPosition; }

    std::optional<LightSample> sampleLi(const vec3& p, const vec2&, const SampledWavelengths& wl) const override {
        LightSample ls;
        const vec3 d = position_ - p;
        const float dist2 = glm::dot(d, d);
        if (dist2 <= 0) return std::nullopt;
        ls.wi = d / std::sqrt(dist2);
        ls.pLight = position_;
        ls.pdf = 1.0f;
        const float falloff = this->falloff(glm::dot(-ls.wi, axis_));
        if (falloff <= 0) return std::nullopt;
        ls.L = intensity_->sample(wl) * (falloff / dist2);
        return ls;
    }

private:
    float falloff(float cosTheta) const {
        if (cosCutoff_ <= -1.0f) return 1.0f;  // point light
        if (cosTheta <= cosCutoff_) return 0.0f;
        if (cosTheta >= cosBeam_) return 1.0f;
        const float t = (cosTheta - cosCutoff_) / (cosBeam_ - cosCutoff_);
        return t * t * (3.0f - 2.0f * t);  // smoothstep
    }

    vec3 position_, axis_;
    SpectrumPtr intensity_;
    float cosCutoff_, cosBeam_;
};

std::shared_ptr<Light> createPoint(const Properties& p) {
    mat4 m = p.getTransform("to_world");
    if (p.has("position")) m = glm::translate(mat4(1.0f), p.getPoint("position")) * m;
    return std::make_shared<SpotLight>(m, getSpectrum(p, "intensity", SpectrumKind::Illuminant, 1.0f), -2.0f, -2.0f);
}

std::shared_ptr<Light> createSpot(const Properties& p) {
    const float cutoff = p.getFloat("cutoff_angle", 20.0f);
    const float beam = p.getFloat("beam_width", cutoff * 0.75f);
    if (!(cutoff > 0 && cutoff <= 180)) failAt(p.locationOf("cutoff_angle"), "spot cutoff_angle must be in (0, 180] degrees");
    if (!(beam > 0 && beam <= cutoff)) failAt(p.locationOf("beam_width"), "spot beam_width must be in (0, cutoff_angle]");
    return std::make_shared<SpotLight>(p.getTransform("to_world"), getSpectrum(p, "intensity", SpectrumKind::Illuminant, 1.0f),
                                       std::cos(glm::radians(cutoff)), std::cos(glm::radians(beam)));
}

}  // namespace

IRIS_REGISTER(LightRegistry, "point", createPoint);
IRIS_REGISTER(LightRegistry, "spot", createSpot);

}  // namespace iris
