#include "render/shapes/shape.h"

namespace iris {

std::shared_ptr<ShapeDescription> meshShape(const Properties& p, TriangleMesh mesh, bool faceNormals) {
    auto s = std::make_shared<ShapeDescription>();
    s->name = !p.id().empty() ? p.id() : p.has("filename") ? p.getString("filename") : p.type();
    mesh.transform(p.getTransform("to_world"));
    if (p.getBool("flip_normals", false)) mesh.flipNormals();
    if (!p.id().empty()) mesh.name = p.id() + " (" + mesh.name + ")";
    s->faceNormals = p.getBool("face_normals", faceNormals);
    if (s->faceNormals) mesh.normals.clear();
    s->mesh = std::make_shared<TriangleMesh>(std::move(mesh));
    return s;
}

}  // namespace iris
