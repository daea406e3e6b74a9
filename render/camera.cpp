#include "render/camera.h"

#include "core/error.h"

namespace iris {

Camera::Camera(const CameraDescription& d) : width_(d.width), height_(d.height) {
    if (width_ <= 0 || height_ <= 0) fail("film size must be positive, got ", width_, "x", height_);
    if (!(d.fovDegrees > 0 && d.fovDegrees < 180)) fail("camera fov must be in (0, 180) degrees, got ", d.fovDegrees);
    origin_ = vec3(d.toWorld[3]);
    toWorld_ = mat3(d.toWorld);
    // Orthonormalise (to_world may contain scale); Mitsuba's lookat gives x = left, y = up, z = forward.
    const float aspect = float(width_) / float(height_);
    const float t = std::tan(glm::radians(d.fovDegrees) * 0.5f);
    using A = CameraDescription::FovAxis;
    A axis = d.fovAxis;
    if (axis == A::Smaller) axis = aspect > 1 ? A::Y : A::X;
    if (axis == A::Larger) axis = aspect > 1 ? A::X : A::Y;
    switch (axis) {
        case A::X: tanHalfX_ = t; tanHalfY_ = t / aspect; break;
        case A::Y: tanHalfY_ = t; tanHalfX_ = t * aspect; break;
        default: {  // diagonal
            const float diag = std::sqrt(aspect * aspect + 1.0f);
            tanHalfX_ = t * aspect / diag;
            tanHalfY_ = t / diag;
        }
    }
}

Ray Camera::generateRay(const vec2& filmPos) const {
    // Normalised device coordinates in [-1, 1]; image x grows to the right, which is the camera's
    // −x (Mitsuba's lookat frame has +x to the left), image y grows downwards (camera −y).
    const float nx = 2.0f * filmPos.x / width_ - 1.0f;
    const float ny = 2.0f * filmPos.y / height_ - 1.0f;
    const vec3 dLocal(-nx * tanHalfX_, -ny * tanHalfY_, 1.0f);
    return Ray(origin_, glm::normalize(toWorld_ * dLocal));
}

}  // namespace iris
