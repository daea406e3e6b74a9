// Perspective pinhole camera (Mitsuba "perspective" sensor): looks along +z of its to_world frame,
// +y up; the field of view applies to the axis chosen by fov_axis.
#pragma once

#include "render/sensors/field_of_view.h"
#include "render/sensors/sensor.h"

namespace iris {

class PerspectiveSensor final : public Sensor {
public:
    PerspectiveSensor(const mat4& toWorld, float fovDegrees, FovAxis axis, FilmSize film);
    Ray generateRay(const vec2& filmPos) const override;
    std::optional<SensorSample> sampleWi(const vec3& p) const override;
    std::optional<vec3> pinhole() const override { return origin_; }
    float pdfDirection(const vec3& w) const override;
    float fovDegrees() const { return fovDegrees_; }
    FovAxis fovAxis() const { return axis_; }

private:
    float fovDegrees_;
    FovAxis axis_;
    int width_, height_;
    vec3 origin_;
    mat3 rotation_;
    mat3 toCamera_;  // inverse of rotation_
    float tanHalfX_, tanHalfY_;
};

}  // namespace iris
