// The analytic sphere (Mitsuba "sphere"): center and radius, placed by a to_world that may only
// rotate, translate and scale uniformly (a sphere stays a sphere); the rotation turns its uv. The scene traces it as Embree
// user geometry with the analytic test of core/sphere_intersection.h (render/scene.cpp).
#include "render/shapes/shape.h"

namespace iris {

namespace {

std::shared_ptr<ShapeDescription> createSphere(const Properties& p) {
    auto s = std::make_shared<ShapeDescription>();
    s->type = ShapeDescription::Type::Sphere;
    s->name = !p.id().empty() ? p.id() : p.type();
    const mat4 toWorld = p.getTransform("to_world");
    const vec3 c = p.getPoint("center", vec3(0.0f));
    const float r = p.getFloat("radius", 1.0f);
    if (!(r > 0)) failAt(p.locationOf("radius"), "sphere radius must be positive");
    s->center = transformPoint(toWorld, c);
    const float scale = uniformScale(toWorld, p.locationOf("to_world"), "sphere");
    s->radius = r * scale;
    // Mitsuba 3 (src/shapes/sphere.cpp) computes uv and ∂p/∂u, ∂p/∂v in the sphere's object space:
    // a rotated sphere's texture turns with it.
    s->frame = mat3(toWorld) / scale;
    s->rotated = s->frame != mat3(1.0f);
    s->flipNormals = p.getBool("flip_normals", false);
    return s;
}

}  // namespace

IRIS_REGISTER(ShapeRegistry, "sphere", createSphere);

}  // namespace iris
