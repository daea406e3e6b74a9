#include "render/shapes/shape.h"

namespace iris {

float uniformScale(const mat4& m, const SourceLocation& loc, const std::string& plugin) {
    const mat3 a(m);
    const float sx = glm::length(a[0]), sy = glm::length(a[1]), sz = glm::length(a[2]);
    const float tol = 1e-4f * std::max({sx, sy, sz});
    if (std::abs(sx - sy) > tol || std::abs(sx - sz) > tol || std::abs(glm::dot(a[0], a[1])) > tol * sx ||
        std::abs(glm::dot(a[0], a[2])) > tol * sx || std::abs(glm::dot(a[1], a[2])) > tol * sy)
        failAt(loc, plugin, ": to_world must be a rotation, translation and uniform scale");
    if (!(sx > 0)) failAt(loc, plugin, ": to_world has a zero scale");
    return sx;
}

}  // namespace iris
