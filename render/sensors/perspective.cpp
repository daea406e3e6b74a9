#include "render/sensors/perspective.h"

namespace iris {

PerspectiveSensor::PerspectiveSensor(const mat4& toWorld, float fovDegrees, FovAxis axis, FilmSize film)
    : Sensor(toWorld), fovDegrees_(fovDegrees), axis_(axis), width_(film.width), height_(film.height) {
    if (width_ <= 0 || height_ <= 0) fail("film size must be positive, got ", width_, "x", height_);
    if (!(fovDegrees > 0 && fovDegrees < 180)) fail("camera fov must be in (0, 180) degrees, got ", fovDegrees);
    origin_ = vec3(toWorld[3]);
    rotation_ = mat3(toWorld);
    toCamera_ = glm::inverse(rotation_);
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

// The importance of a pinhole (pbrt-v4 §5.4.1, Veach 1997 §10.2): a film position uniform over the
// image's area A = 4 tan(fov_x/2) tan(fov_y/2) on the plane z = 1 leaves the pinhole in direction w
// with the solid-angle density 1 / (A cos³θ), θ the angle to the view axis. Normalised to the
// image's W H pixels, the importance per unit solid angle is W H / (A cos³θ); a scene point at
// distance d is reached through a solid angle |cos θ_p| dA / d².
std::optional<SensorSample> PerspectiveSensor::sampleWi(const vec3& p) const {
    const vec3 toP = p - origin_;
    const float dist2 = glm::dot(toP, toP);
    if (!(dist2 > 0)) return std::nullopt;
    const vec3 local = toCamera_ * toP;
    if (!(local.z > 0)) return std::nullopt;
    SensorSample s;
    s.pSensor = origin_;
    s.dist = std::sqrt(dist2);
    s.wi = -toP / s.dist;
    // generateRay's mapping inverted: dLocal = (−nx tanX, −ny tanY, 1).
    const float nx = -local.x / (local.z * tanHalfX_), ny = -local.y / (local.z * tanHalfY_);
    s.filmPos = vec2(0.5f * (nx + 1.0f) * float(width_), 0.5f * (ny + 1.0f) * float(height_));
    s.weight = float(width_) * float(height_) * pdfDirection(-s.wi) / dist2;
    return s;
}

float PerspectiveSensor::pdfDirection(const vec3& w) const {
    const vec3 local = toCamera_ * w;
    const float cosTheta = local.z / glm::length(local);
    if (!(cosTheta > 0)) return 0.0f;
    return 1.0f / (4.0f * tanHalfX_ * tanHalfY_ * cosTheta * cosTheta * cosTheta);
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
