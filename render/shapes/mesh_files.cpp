// Shapes read from mesh files: Wavefront OBJ, PLY and Mitsuba's serialized format. Reader errors
// name the file; withLocation adds the scene line that asked for it.
#include "core/io/obj_reader.h"
#include "core/io/ply_reader.h"
#include "core/io/serialized_reader.h"
#include "render/shapes/shape.h"

namespace iris {

namespace {

std::shared_ptr<ShapeDescription> createObj(const Properties& p) {
    TriangleMesh mesh = withLocation(p.locationOf("filename"), [&] { return readObj(p.getString("filename")); });
    if (!p.getBool("flip_tex_coords", true))  // the reader flips v like Mitsuba; undo on request
        for (vec2& uv : mesh.uvs) uv.y = 1.0f - uv.y;
    return meshShape(p, std::move(mesh));
}

std::shared_ptr<ShapeDescription> createPly(const Properties& p) {
    return meshShape(p, withLocation(p.locationOf("filename"), [&] { return readPly(p.getString("filename")); }));
}

std::shared_ptr<ShapeDescription> createSerialized(const Properties& p) {
    const int index = p.getInt("shape_index", 0);
    SerializedMesh sm = withLocation(p.locationOf("filename"), [&] { return readSerialized(p.getString("filename"), index); });
    return meshShape(p, std::move(sm.mesh), sm.faceNormals);
}

}  // namespace

IRIS_REGISTER(ShapeRegistry, "obj", createObj);
IRIS_REGISTER(ShapeRegistry, "ply", createPly);
IRIS_REGISTER(ShapeRegistry, "serialized", createSerialized);

}  // namespace iris
