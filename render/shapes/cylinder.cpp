// The analytic open cylinder (Mitsuba "cylinder", src/shapes/cylinder.cpp): the centre line from
// `p0` (default (0, 0, 0)) to `p1` (default (0, 0, 1)), `radius` (default 1), no end caps,
// `flip_normals` (default false: normals point outwards), placed by a `to_world` that may rotate,
// translate, scale the axis (the length) and scale uniformly across it. uv as Mitsuba 3: u = φ/2π
// around the axis, measured in the frame Frame3f(axis) (Frame::fromNormal), v = the position along the axis / length. The scene
// traces it as Embree user geometry (core/cylinder_intersection.h, render/scene.cpp); an area
// emitter on it is sampled uniformly by area.
#include "core/frame.h"
#include "render/shapes/shape.h"

namespace iris {

namespace {

/// The scale of the linear map `lin` across the cylinder's axis (`local` is the object-space frame
/// of the axis). As Mitsuba 3 (Cylinder::update, which decomposes to_world · [radius, radius,
/// length]): the two directions across the axis must be scaled equally, and nothing may shear
/// them against each other or against the axis; the axis itself may be scaled freely (the length).
float radialScale(const mat3& lin, const Frame& local, const SourceLocation& loc) {
    const vec3 s = lin * local.s, t = lin * local.t, n = lin * local.n;
    const float ls = glm::length(s), lt = glm::length(t), ln = glm::length(n);
    const float tol = 1e-4f * std::max({ls, lt, ln});
    if (!(ls > 0) || !(ln > 0) || !std::isfinite(ls * ln)) failAt(loc, "cylinder: to_world has a zero or infinite scale");
    if (std::abs(ls - lt) > tol)
        failAt(loc, "cylinder: to_world must scale the two directions across the axis equally (Mitsuba 3 refuses this too)");
    if (std::abs(glm::dot(s, t)) > tol * ls || std::abs(glm::dot(s, n)) > tol * ln || std::abs(glm::dot(t, n)) > tol * ln)
        failAt(loc, "cylinder: to_world must not shear (Mitsuba 3 refuses this too)");
    return ls;
}

std::shared_ptr<ShapeDescription> createCylinder(const Properties& p) {
    auto s = std::make_shared<ShapeDescription>();
    s->type = ShapeDescription::Type::Cylinder;
    s->name = !p.id().empty() ? p.id() : p.type();
    const mat4 toWorld = p.getTransform("to_world");
    const vec3 p0 = p.getPoint("p0", vec3(0.0f)), p1 = p.getPoint("p1", vec3(0.0f, 0.0f, 1.0f));
    const float r = p.getFloat("radius", 1.0f);
    if (!(r > 0) || !std::isfinite(r)) failAt(p.locationOf("radius"), "cylinder radius must be positive, got ", r);
    const vec3 w0 = transformPoint(toWorld, p0), w1 = transformPoint(toWorld, p1);
    const float length = glm::length(w1 - w0);
    if (!(length > 0) || !std::isfinite(length))
        failAt(p.has("p1") ? p.locationOf("p1") : p.location(), "cylinder: p0 and p1 must be distinct finite points");
    CylinderGeometry& c = s->cylinder;
    c.p0 = w0;
    c.length = length;
    // The frame of the object-space axis, carried to world space by to_world (a rotation and a
    // uniform scale, so the frame stays orthonormal once normalised).
    const Frame local = Frame::fromNormal(glm::normalize(p1 - p0));
    const mat3 lin(toWorld);
    const float k = radialScale(lin, local, p.locationOf("to_world"));
    c.axis = glm::normalize(lin * local.n);
    c.s = glm::normalize(lin * local.s);
    c.t = glm::normalize(lin * local.t);  // = axis × s unless to_world mirrors
    s->radius = r * k;
    s->flipNormals = p.getBool("flip_normals", false);
    return s;
}

}  // namespace

IRIS_REGISTER(ShapeRegistry, "cylinder", createCylinder);

}  // namespace iris
