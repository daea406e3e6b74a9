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
    const float aspect = float(width_) / float(height_);
    const float t = std::tan(glm::radians(fovDegrees) * 0.5f);
    if (axis == FovAxis::Smaller) axis = aspect > 1 ? FovAxis::Y : FovAxis::X;
    if (axis == FovAxis::Larger) axis = aspect > 1 ? FovAxis::X : FovAxis::Y;
    switch (axis) {
        case FovAxis::X: tanHalfX_ = t; tanHalfY_ = t / aspect; break;
        case FovAxis::Y: tanHalfY_ = t; tanHalfX_ = t * aspect; break;
        default: {  // diagonal
            const float diag = std::sqrt(aspect * aspect + 1.0f);
            tanHalfX_ = t * aspect / diag;
            tanHalfY_ = t / diag;
        }
    }
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

FovAxis parseFovAxis(const Properties& p) {
    const std::string axis = p.getString("fov_axis", "x");
    if (axis == "x") return FovAxis::X;
    if (axis == "y") return FovAxis::Y;
    if (axis == "diagonal") return FovAxis::Diagonal;
    if (axis == "smaller") return FovAxis::Smaller;
    if (axis == "larger") return FovAxis::Larger;
    failAt(p.locationOf("fov_axis"), "fov_axis '", axis, "' is not one of x, y, diagonal, smaller, larger");
}

std::shared_ptr<Sensor> createPerspective(const Properties& p, FilmSize film) {
    const mat4 toWorld = p.getTransform("to_world");
    // Default: a 50 mm lens on 36 mm-wide film, fov_x = 2 atan(18 / 50) ≈ 39.6°.
    const float fov = p.getFloat("fov", 2.0f * std::atan(18.0f / 50.0f) * 180.0f / kPi);
    if (!(fov > 0 && fov < 180)) failAt(p.locationOf("fov"), "fov must be in (0, 180) degrees");
    const FovAxis axis = parseFovAxis(p);
    // Accepted and ignored: a pinhole camera has no clipping planes or focus.
    p.getFloat("near_clip", 0.01f);
    p.getFloat("far_clip", 1e4f);
    p.getFloat("focus_distance", 0.0f);
    return std::make_shared<PerspectiveSensor>(toWorld, fov, axis, film);
}

}  // namespace

IRIS_REGISTER(SensorRegistry, "perspective", createPerspective);

}  // namespace iris
