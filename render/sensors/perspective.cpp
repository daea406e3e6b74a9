#include "render/sensors/perspective.h"

#include <cstdlib>

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

/// A focal length "50mm" (or "50") in 35 mm-film-equivalent millimetres.
float parseFocalLength(const Properties& p) {
    std::string f = p.getString("focal_length", "50mm");
    if (f.size() > 2 && f.compare(f.size() - 2, 2, "mm") == 0) f.resize(f.size() - 2);
    char* end = nullptr;
    const float v = std::strtof(f.c_str(), &end);
    if (f.empty() || end != f.c_str() + f.size() || !(v > 0) || !std::isfinite(v))
        failAt(p.locationOf("focal_length"), "focal_length '", p.getString("focal_length"), "' must be a positive length like \"50mm\"");
    return v;
}

std::shared_ptr<Sensor> createPerspective(const Properties& p, FilmSize film) {
    const mat4 toWorld = p.getTransform("to_world");
    // Mitsuba 3 (src/render/sensor.cpp, parse_fov) and 0.6 alike: `fov` along `fov_axis` (default
    // x), or else `focal_length` (0.6: focalLength; default 50 mm) on a 36 × 24 mm film measured
    // along its diagonal, fov = 2 atan(√(36² + 24²) / (2 f)) (46.79° for 50 mm), fov_axis ignored.
    float fov;
    FovAxis axis;
    if (p.has("fov")) {
        if (p.has("focal_length")) failAt(p.locationOf("focal_length"), "give either fov or focal_length, not both");
        fov = p.getFloat("fov");
        if (!(fov > 0 && fov < 180)) failAt(p.locationOf("fov"), "fov must be in (0, 180) degrees");
        axis = parseFovAxis(p);
    } else {
        const float f = parseFocalLength(p);
        fov = 2.0f * std::atan(std::sqrt(36.0f * 36.0f + 24.0f * 24.0f) / (2.0f * f)) * 180.0f / kPi;
        axis = FovAxis::Diagonal;
        p.getString("fov_axis", "x");  // accepted; Mitsuba ignores it with a focal length
    }
    // Accepted and ignored: a pinhole camera has no clipping planes or focus.
    p.getFloat("near_clip", 0.01f);
    p.getFloat("far_clip", 1e4f);
    p.getFloat("focus_distance", 0.0f);
    return std::make_shared<PerspectiveSensor>(toWorld, fov, axis, film);
}

}  // namespace

IRIS_REGISTER(SensorRegistry, "perspective", createPerspective);

}  // namespace iris
