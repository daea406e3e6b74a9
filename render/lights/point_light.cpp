// Point and spot lights (Mitsuba "point", "spot"). Radiant intensity I (per steradian):
// L arriving at distance d is I/d². Spot (Mitsuba 0.6 src/emitters/spot.cpp and Mitsuba 3
// src/emitters/spot.cpp, the same in both): full intensity within beam_width of the axis, none
// beyond cutoff_angle, and in between a falloff linear in the angle θ from the axis,
// (cutoff − θ)/(cutoff − beam_width); an optional `texture` (spatially varying, e.g. a bitmap)
// multiplies the intensity, projected along the axis: a direction (x, y, z) in the light's frame
// looks it up at uv = ½ + ½ (x, y) / (z tan cutoff) (Mitsuba 3 direction_to_uv).
#include "render/lights/light.h"
#include "core/frame.h"
#include "core/registry.h"
#include "core/sampling.h"
#include "materials/textures/texture_params.h"
#include "spectral/spectrum.h"
#include "spectral/spectrum_params.h"

namespace iris {
namespace {

class SpotLight final : public Light {
public:
    /// cutoff and beam in radians; cutoff < 0: a point light (no falloff). texture may be null.
    SpotLight(const mat4& toWorld, SpectrumPtr intensity, float cutoff, float beam, SpectrumTexturePtr texture = nullptr)
        : position_(transformPoint(toWorld, vec3(0.0f))),
          axis_(glm::normalize(transformVector(toWorld, vec3(0, 0, 1)))),
          toLocal_(glm::inverse(mat3(toWorld))),
          intensity_(std::move(intensity)), texture_(std::move(texture)), cutoff_(cutoff), beam_(beam),
          cosCutoff_(std::cos(cutoff)), cosBeam_(std::cos(beam)), uvFactor_(std::tan(cutoff)), frame_(Frame::fromNormal(axis_)) {}

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
        if (texture_) ls.L *= textureAt(-ls.wi, wl);
        return ls;
    }

    /// A ray from the light's position: directions uniform on the sphere (point) or in the cone of
    /// cutoff_angle (spot), carrying the radiant intensity (pbrt-v4 §12.2.1 PointLight::SampleLe,
    /// SpotLight::SampleLe).
    std::optional<LightEmission> sampleLe(const vec2&, const vec2& uDir, const SampledWavelengths& wl,
                                          const SceneBounds&) const override {
        const float cosMax = cutoff_ < 0.0f ? -1.0f : cosCutoff_;
        LightEmission e;
        e.ray = Ray(position_, glm::normalize(frame_.toWorld(sampleUniformCone(uDir, cosMax))));
        const float falloff = this->falloff(glm::dot(e.ray.d, axis_));
        if (falloff <= 0) return std::nullopt;
        e.L = intensity_->sample(wl) * falloff;
        if (texture_) e.L *= textureAt(e.ray.d, wl);
        e.pdfPos = 1.0f;
        e.pdfDir = uniformConePdf(cosMax);
        return e;
    }
    vec2 pdfLe(const vec3&, const vec3&, const vec3& w, const SceneBounds&) const override {
        const float cosMax = cutoff_ < 0.0f ? -1.0f : cosCutoff_;
        return vec2(0.0f, glm::dot(w, axis_) >= cosMax ? uniformConePdf(cosMax) : 0.0f);
    }

private:
    /// The projected texture towards direction w (world, leaving the light).
    SampledSpectrum textureAt(const vec3& w, const SampledWavelengths& wl) const {
        const vec3 local = toLocal_ * w;  // Mitsuba 3 direction_to_uv
        TextureQuery q;
        q.uv = vec2(0.5f + 0.5f * local.x / (local.z * uvFactor_), 0.5f + 0.5f * local.y / (local.z * uvFactor_));
        return texture_->eval(q, wl);
    }

    float falloff(float cosTheta) const {
        if (cutoff_ < 0.0f) return 1.0f;  // point light
        if (!(cosTheta > cosCutoff_)) return 0.0f;
        if (cosTheta >= cosBeam_) return 1.0f;
        return (cutoff_ - safeAcos(cosTheta)) / (cutoff_ - beam_);  // linear in the angle (Mitsuba)
    }

    vec3 position_, axis_;
    mat3 toLocal_;
    SpectrumPtr intensity_;
    SpectrumTexturePtr texture_;
    float cutoff_, beam_, cosCutoff_, cosBeam_, uvFactor_;
    Frame frame_;  // around the axis, for emission sampling
};

std::shared_ptr<Light> createPoint(const Properties& p) {
    mat4 m = p.getTransform("to_world");
    if (p.has("position")) m = glm::translate(mat4(1.0f), p.getPoint("position")) * m;
    return std::make_shared<SpotLight>(m, getSpectrum(p, "intensity", SpectrumKind::Illuminant, 1.0f), -1.0f, -1.0f);
}

std::shared_ptr<Light> createSpot(const Properties& p) {
    const float cutoff = p.getFloat("cutoff_angle", 20.0f);
    const float beam = p.getFloat("beam_width", cutoff * 0.75f);
    if (!(cutoff > 0 && cutoff <= 180)) failAt(p.locationOf("cutoff_angle"), "spot cutoff_angle must be in (0, 180] degrees");
    if (!(beam > 0 && beam <= cutoff)) failAt(p.locationOf("beam_width"), "spot beam_width must be in (0, cutoff_angle]");
    SpectrumTexturePtr texture;
    if (p.has("texture")) {
        // Mitsuba 3: "The parameter 'texture' must be spatially varying (e.g. bitmap type)!"; a
        // reflectance-like colour (no D65 factor: the intensity carries the illuminant).
        texture = getSpectrumTexture(p, "texture", SpectrumKind::Reflectance);
        if (texture->isConstant())
            failAt(p.locationOf("texture"), "spot: 'texture' must be spatially varying (a bitmap or checkerboard "
                   "texture); for a constant colour give 'intensity' instead");
        if (!(cutoff < 90))
            failAt(p.locationOf("cutoff_angle"), "spot: a projected texture needs cutoff_angle < 90 degrees, got ", cutoff);
    }
    return std::make_shared<SpotLight>(p.getTransform("to_world"), getSpectrum(p, "intensity", SpectrumKind::Illuminant, 1.0f),
                                       glm::radians(cutoff), glm::radians(beam), texture);
}

}  // namespace

IRIS_REGISTER(LightRegistry, "point", createPoint);
IRIS_REGISTER(LightRegistry, "spot", createSpot);

}  // namespace iris
