#include "core/transforms.h"

#include <glm/gtc/matrix_transform.hpp>

namespace iris {

mat4 lookAtMatrix(const vec3& origin, const vec3& target, const vec3& up, const SourceLocation& loc) {
    const vec3 d = target - origin;
    if (!(glm::length(d) > 0)) failAt(loc, "lookat: origin and target coincide");
    const vec3 dir = glm::normalize(d);
    const vec3 l = glm::cross(up, dir);
    if (!(glm::length(l) > 1e-6f * glm::length(up))) failAt(loc, "lookat: up vector is zero or parallel to the view direction");
    const vec3 left = glm::normalize(l);
    const vec3 newUp = glm::cross(dir, left);
    mat4 m(1.0f);
    m[0] = vec4(left, 0.0f);
    m[1] = vec4(newUp, 0.0f);
    m[2] = vec4(dir, 0.0f);
    m[3] = vec4(origin, 1.0f);
    return m;
}

mat4 rotationMatrix(const vec3& axis, float degrees, const SourceLocation& loc) {
    if (!(glm::length(axis) > 0)) failAt(loc, "rotate: the axis is zero");
    return glm::rotate(mat4(1.0f), glm::radians(degrees), glm::normalize(axis));
}

}  // namespace iris
