#include "render/sensors/perspective.h"

namespace iris {

PerspectiveSensor::PerspectiveSensor(const mat4& toWorld, float fovDegrees, FovAxis axis, FilmSize film)
    : Sensor(toWorld), fovDegrees_(fovDegrees), axis_(axis), width_(film.width), height_(film.height) {
    if (width_ <= 0 || height_ <= 0) fail("film size must be positive, got ", width_, "x", height_);
    if (!(fovDegrees > 0 && fovDegrees < 180)) fail("camera fov must be in (0, 180) degrees, got ", fovDegrees);
    origin_ = vec3(toWorld[3]);
    rotation_ = mat3(toWorld);
    // Directions are normalised per ray (to_world may contain scale); Mitsuba's lookat gives
    // x = left, y = up, z = forward.
    const vec2 tanHalf = tanHalfAngles({fovDegrees, axis}, float(width_) / float(height_));
    tanHalfX_ = tanHalf.x;
    tanHalfY_ = tanHalf.y;
}

Ray PerspectiveSensor::generateRay(const vec2& filmPos) const {
    // Normalised device coordinates in [-1, 1]; image x grows to the right, which is the camera's
    // −x (Mitsuba's lookat frame has +x to the left), image y grows downwards (camera −y).
    const float nx = 2.0f * filmPos.x / width_ - 1.0f;
    const float ny = 2.0f * filmPos.y / height_ - 1.0f;
    const vec3 dLocal(-nx * tanHalfX_, -ny * tanHalfY_, 1.0f);
    return Ray(origin_, glm::normalize(rotation_ * dLocal));
}

namespace {

std::shared_ptr<Sensor> createPerspective(const Properties& p, FilmSize film) {
    const mat4 toWorld = p.getTransform("to_world");
    const FieldOfView fov = parseFieldOfView(p);
    // Accepted and ignored: a pinhole camera has no clipping planes or focus.
    p.getFloat("near_clip", 0.01f);
    p.getFloat("far_clip", 1e4f);
    p.getFloat("focus_distance", 0.0f);
    return std::make_shared<PerspectiveSensor>(toWorld, fov.degrees, fov.axis, film);
}

}  // namespace

IRIS_REGISTER(SensorRegistry, "perspective", createPerspective);

}  // namespace iris
