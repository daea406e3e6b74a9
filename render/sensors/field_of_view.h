// A pinhole's field of view as Mitsuba's scene files give it (`fov` along `fov_axis`, or a 35 mm
// `focal_length`), shared by the perspective sensor and the projector emitter, which Mitsuba 3
// parses alike (src/render/sensor.cpp, parse_fov).
#pragma once

#include "core/math.h"
#include "core/properties.h"

namespace iris {

enum class FovAxis { X, Y, Diagonal, Smaller, Larger };

struct FieldOfView {
    float degrees = 0.0f;
    FovAxis axis = FovAxis::X;
};

/// `fov` (degrees, in (0, 180)) along `fov_axis` (default x), or else `focal_length` (default
/// "50mm"), which gives a diagonal field of view; located errors for bad values or both given.
FieldOfView parseFieldOfView(const Properties& p);

/// tan of the half-angles along the image's x and y for an image of aspect width/height.
vec2 tanHalfAngles(const FieldOfView& fov, float aspect);

}  // namespace iris
