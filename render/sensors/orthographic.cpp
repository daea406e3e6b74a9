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
    }

    Ray generateRay(const vec2& filmPos) const override {
        const float aspect = float(width_) / float(height_);
        const float nx = 2.0f * filmPos.x / width_ - 1.0f;
        const float ny = 2.0f * filmPos.y / height_ - 1.0f;
        const vec3 local(-nx, -ny / aspect, nearClip_);
        return Ray(vec3(toWorld() * vec4(local, 1.0f)), direction_);
    }

private:
    int width_, height_;
    float nearClip_;
    vec3 direction_;
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
