// The analytic sphere (Mitsuba "sphere"): center and radius, placed by a to_world that may only
// rotate, translate and scale uniformly (a sphere stays a sphere). The scene traces it as Embree
// user geometry with the analytic test of render/sphere_intersection.h (render/scene.cpp).
#include "render/shapes/shape.h"

namespace iris {

namespace {

/// Uniform scale factor of a transform's linear part, or an error for a non-uniform scale / shear.
float uniformScale(const mat4& m, const SourceLocation& loc) {
    const mat3 a(m);
    const float sx = glm::length(a[0]), sy = glm::length(a[1]), sz = glm::length(a[2]);
    const float tol = 1e-4f * std::max({sx, sy, sz});
    if (std::abs(sx - sy) > tol || std::abs(sx - sz) > tol || std::abs(glm::dot(a[0], a[1])) > tol * sx ||
        std::abs(glm::dot(a[0], a[2])) > tol * sx || std::abs(glm::dot(a[1], a[2])) > tol * sy)
        failAt(loc, "sphere: to_world must be a rotation, translation and uniform scale");
    if (!(sx > 0)) failAt(loc, "sphere: to_world has a zero scale");
    return sx;
}

std::shared_ptr<ShapeDescription> createSphere(const Properties& p) {
    auto s = std::make_shared<ShapeDescription>();
    s->type = ShapeDescription::Type::Sphere;
    s->name = !p.id().empty() ? p.id() : p.type();
    const mat4 toWorld = p.getTransform("to_world");
    const vec3 c = p.getPoint("center", vec3(0.0f));
    const float r = p.getFloat("radius", 1.0f);
    if (!(r > 0)) failAt(p.locationOf("radius"), "sphere radius must be positive");
    s->center = transformPoint(toWorld, c);
    s->radius = r * uniformScale(toWorld, p.locationOf("to_world"));
    s->flipNormals = p.getBool("flip_normals", false);
    return s;
}

}  // namespace

IRIS_REGISTER(ShapeRegistry, "sphere", createSphere);

}  // namespace iris
