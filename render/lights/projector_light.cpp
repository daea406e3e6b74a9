// Projector (Mitsuba 3 "projector", src/emitters/projector.cpp; Mitsuba 0.6 has none): the
// reciprocal of the perspective camera. A pinhole at the origin of to_world, looking along +z,
// projects the `irradiance` texture, which lies on its virtual image plane at z = 1, into the
// scene. A point p in the projector's frame (x, y, z), z > 0, is reached through the image point
//   u = ½ − ½ x / (z tan(fov_x/2)),   v = ½ − ½ y / (z tan(fov_y/2))
// (Mitsuba 3's camera_to_sample of perspective_projection, the perspective sensor's mapping:
// image x runs along the frame's −x, image y down its −y), and receives
//   L = π · scale · D65 · E(u, v) / (z² cos θ)          (Mitsuba 3 Projector::sample_direction)
// where θ is the angle between +z and the direction to p: irradiance π·scale·E on the plane z = 1.
// Outside the image (u or v outside [0, 1]) or behind the projector nothing arrives. The field of
// view is parsed as the perspective sensor's (fov / fov_axis / focal_length) with the texture's
// width/height as the aspect ratio.
#include "render/lights/light.h"
#include "core/registry.h"
#include "materials/textures/texture_params.h"
#include "render/sensors/field_of_view.h"
#include "spectral/spectrum.h"
#include "spectral/spectrum_params.h"

namespace iris {
namespace {

class ProjectorLight final : public Light {
public:
    ProjectorLight(const mat4& toWorld, SpectrumTexturePtr irradiance, SpectrumPtr intensity, vec2 tanHalf)
        : position_(transformPoint(toWorld, vec3(0.0f))), axis_(glm::normalize(transformVector(toWorld, vec3(0, 0, 1)))),
          toLocal_(glm::inverse(toWorld)), irradiance_(std::move(irradiance)), intensity_(std::move(intensity)),
          tanHalf_(tanHalf) {}

    Type type() const override { return Type::DeltaPosition; }

    std::optional<LightSample> sampleLi(const vec3& p, const vec2&, const SampledWavelengths& wl) const override {
        const vec3 local = transformPoint(toLocal_, p);
        if (!(local.z > 0.0f)) return std::nullopt;
        TextureQuery q;
        q.uv = vec2(0.5f - 0.5f * local.x / (local.z * tanHalf_.x), 0.5f - 0.5f * local.y / (local.z * tanHalf_.y));
        if (!(q.uv.x >= 0.0f && q.uv.x <= 1.0f && q.uv.y >= 0.0f && q.uv.y <= 1.0f)) return std::nullopt;
        const vec3 d = position_ - p;
        const float dist = glm::length(d);
        LightSample ls;
        ls.wi = d / dist;
        ls.pLight = position_;
        ls.pdf = 1.0f;
        const float cosTheta = -glm::dot(axis_, ls.wi);
        if (!(cosTheta > 0.0f)) return std::nullopt;
        ls.L = irradiance_->eval(q, wl) * intensity_->sample(wl) * (kPi / (local.z * local.z * cosTheta));
        return ls;
    }

    /// A ray through a point of the image drawn uniformly in (u, v): the direction's density is
    /// 1 / (4 tan(fov_x/2) tan(fov_y/2) cos³θ) (the image plane z = 1 seen from the pinhole, as the
    /// perspective camera's importance, pbrt-v4 §5.4.1), and it carries the intensity I = L d² of
    /// sampleLi's radiance at unit distance.
    std::optional<LightEmission> sampleLe(const vec2&, const vec2& uDir, const SampledWavelengths& wl,
                                          const SceneBounds&) const override {
        const vec3 local((1.0f - 2.0f * uDir.x) * tanHalf_.x, (1.0f - 2.0f * uDir.y) * tanHalf_.y, 1.0f);
        const vec3 d = glm::normalize(vec3(glm::inverse(toLocal_) * vec4(local, 0.0f)));
        const std::optional<LightSample> ls = sampleLi(position_ + d, vec2(0.0f), wl);
        if (!ls) return std::nullopt;
        LightEmission e;
        e.ray = Ray(position_, d);
        e.L = ls->L;  // at distance 1: the intensity
        e.pdfPos = 1.0f;
        e.pdfDir = pdfLe(position_, vec3(0.0f), d, SceneBounds{}).y;
        return e;
    }
    vec2 pdfLe(const vec3&, const vec3&, const vec3& w, const SceneBounds&) const override {
        const vec3 local = vec3(toLocal_ * vec4(w, 0.0f));
        if (!(local.z > 0.0f)) return vec2(0.0f);
        const vec2 t(local.x / local.z, local.y / local.z);
        if (std::abs(t.x) > tanHalf_.x || std::abs(t.y) > tanHalf_.y) return vec2(0.0f);
        const float cosTheta = local.z / glm::length(local);
        return vec2(0.0f, 1.0f / (4.0f * tanHalf_.x * tanHalf_.y * cosTheta * cosTheta * cosTheta));
    }

private:
    vec3 position_, axis_;
    mat4 toLocal_;
    SpectrumTexturePtr irradiance_;
    SpectrumPtr intensity_;
    vec2 tanHalf_;
};

std::shared_ptr<Light> createProjector(const Properties& p) {
    // An image texture (a bitmap) is a colour in [0, 1] (upsampled as a reflectance, as Mitsuba 3's
    // bitmap does); a plain value inside an emitter is Mitsuba 3's unbounded sRGB spectrum. The
    // illuminant is D65 × scale (Mitsuba 3: m_intensity = Texture::D65(scale)).
    const SpectrumKind kind = p.peekObject("irradiance") ? SpectrumKind::Reflectance : SpectrumKind::Unbounded;
    SpectrumTexturePtr irradiance = getSpectrumTexture(p, "irradiance", kind);
    const ivec2 res = irradiance->resolution();
    const vec2 tanHalf = tanHalfAngles(parseFieldOfView(p), float(res.x) / float(res.y));
    const float scale = p.getFloat("scale", 1.0f);
    if (!(scale >= 0.0f) || !std::isfinite(scale)) failAt(p.locationOf("scale"), "projector: scale must be finite and >= 0, got ", scale);
    return std::make_shared<ProjectorLight>(p.getTransform("to_world"), std::move(irradiance),
                                            spectrumFromNumber(scale, SpectrumKind::Illuminant), tanHalf);
}

}  // namespace

IRIS_REGISTER(LightRegistry, "projector", createProjector);

}  // namespace iris
