// Wavefront OBJ triangle meshes: v, vt, vn and f (polygons triangulated as fans, negative
// indices relative to the end); every other statement (o, g, s, usemtl, mtllib, ...) is ignored.
#pragma once

#include <string>

#include "core/mesh.h"

namespace iris {

/// Read an OBJ file. Face corners with the same (v, vt, vn) triple share one output vertex.
/// Texture v is flipped (v' = 1 − v) as in Mitsuba, so that image row 0 is v' = 0.
/// Normals are kept only when every corner has one; uvs when any corner has one (others get 0).
/// Throws iris::Error "path:line: message" on malformed input.
TriangleMesh readObj(const std::string& path);

/// The same, from text already in memory (`name` is used in messages).
TriangleMesh parseObj(const std::string& text, const std::string& name);

}  // namespace iris
