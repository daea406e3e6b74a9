// Orthographic camera (Mitsuba "orthographic"), Mitsuba 3's convention (src/sensors/orthographic.cpp):
// in camera space the film spans x ∈ [−1, 1] and y ∈ [−1/aspect, 1/aspect]; rays start on the
// near-clip plane z = near_clip and travel along +z; to_world places and scales that window (a
// <scale> in to_world sets the visible extent). As for the perspective camera, image x grows
// towards the camera's −x and image y downwards (camera −y).
#include "render/sensors/sensor.h"

namespace iris {

namespace {

class OrthographicSensor final : public Sensor {
public:
    OrthographicSensor(const mat4& toWorld, float nearClip, FilmSize film)
        : Sensor(toWorld), width_(film.width), height_(film.height), nearClip_(nearClip),
          direction_(glm::normalize(vec3(toWorld * vec4(0, 0, 1, 0)))) {
        if (!isFinite(direction_)) fail("orthographic sensor: to_world maps +z to a zero vector");
        toLocal_ = glm::inverse(toWorld);
        // The film window (x ∈ [−1, 1], y ∈ [−1/aspect, 1/aspect]) projected perpendicular to the
        // view direction.
        const float aspect = float(width_) / float(height_);
        const vec3 ex = vec3(toWorld * vec4(2, 0, 0, 0)), ey = vec3(toWorld * vec4(0, 2 / aspect, 0, 0));
        areaPerp_ = std::abs(glm::dot(glm::cross(ex, ey), direction_));
    }

    Ray generateRay(const vec2& filmPos) const override {
        const float aspect = float(width_) / float(height_);
        const float nx = 2.0f * filmPos.x / width_ - 1.0f;
        const float ny = 2.0f * filmPos.y / height_ - 1.0f;
        const vec3 local(-nx, -ny / aspect, nearClip_);
        return Ray(vec3(toWorld() * vec4(local, 1.0f)), direction_);
    }

    /// The point of the film window that sees p along the view direction; the importance is
    /// W H / A⊥ per unit area perpendicular to the rays (Veach 1997 §10.2; a particle at p covers
    /// |cos θ_p| dA of it), whatever the distance.
    std::optional<SensorSample> sampleWi(const vec3& p) const override {
        const vec3 local = vec3(toLocal_ * vec4(p, 1.0f));
        if (!(local.z > nearClip_)) return std::nullopt;
        const float aspect = float(width_) / float(height_);
        SensorSample s;
        s.pSensor = vec3(toWorld() * vec4(local.x, local.y, nearClip_, 1.0f));
        s.dist = glm::length(s.pSensor - p);
        s.wi = -direction_;
        s.filmPos = vec2(0.5f * (1.0f - local.x) * float(width_), 0.5f * (1.0f - local.y * aspect) * float(height_));
        s.weight = float(width_) * float(height_) / areaPerp_;
        return s;
    }

private:
    int width_, height_;
    float nearClip_;
    vec3 direction_;
    mat4 toLocal_;
    float areaPerp_ = 1.0f;
};

std::shared_ptr<Sensor> createOrthographic(const Properties& p, FilmSize film) {
    const mat4 toWorld = p.getTransform("to_world");
    const float nearClip = p.getFloat("near_clip", 0.01f), farClip = p.getFloat("far_clip", 1e4f);
    if (!(nearClip >= 0) || !(farClip > nearClip)) failAt(p.location(), "orthographic: need 0 <= near_clip < far_clip");
    return withLocation(p.location(), [&] { return std::make_shared<OrthographicSensor>(toWorld, nearClip, film); });
}

}  // namespace

IRIS_REGISTER(SensorRegistry, "orthographic", createOrthographic);

}  // namespace iris
