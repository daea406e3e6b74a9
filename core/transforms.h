// The matrices scene transforms are built from (Mitsuba's <lookat> and <rotate>), with errors at
// the scene line that wrote them.
#pragma once

#include "core/error.h"
#include "core/math.h"

namespace iris {

/// Mitsuba's look-at frame: columns (left, up', dir, origin), so the camera looks along +z
/// (Mitsuba 3 Transform::look_at). Errors at `loc`: origin = target, up zero or parallel to the view.
mat4 lookAtMatrix(const vec3& origin, const vec3& target, const vec3& up, const SourceLocation& loc);
/// Rotation by `degrees` about `axis` (right-handed, Rodrigues' formula); a zero axis is an error at `loc`.
mat4 rotationMatrix(const vec3& axis, float degrees, const SourceLocation& loc);

}  // namespace iris
