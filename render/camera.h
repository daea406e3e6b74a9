// Perspective pinhole camera (Mitsuba "perspective" sensor): looks along +z of its to_world frame,
// +y up; the field of view applies to the axis chosen by fov_axis.
#pragma once

#include "core/ray.h"
#include "render/scene_description.h"

namespace iris {

class Camera {
public:
    explicit Camera(const CameraDescription& d);
    /// Primary ray through film position (x, y) in pixels (0,0 = top-left corner). Direction is unit.
    Ray generateRay(const vec2& filmPos) const;
    int width() const { return width_; }
    int height() const { return height_; }

private:
    int width_, height_;
    vec3 origin_;
    mat3 toWorld_;
    float tanHalfX_, tanHalfY_;
};

}  // namespace iris
