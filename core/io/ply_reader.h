// Stanford PLY triangle meshes, ASCII and binary (little and big endian): vertex x y z, optional
// nx ny nz and texture coordinates (u v, s t, texture_u texture_v or texture_s texture_t), face
// lists `vertex_indices` / `vertex_index` of any integer type (polygons triangulated as fans).
// Other scalar properties of vertices and faces become mesh attributes named as Mitsuba 3 names
// them (`vertex_color` from r g b / red green blue, `vertex_<p>`, `face_<p>`; integers normalised
// and sRGB-decoded; see attributeLayouts in the .cpp); other elements and list properties are skipped.
#pragma once

#include <string>

#include "core/mesh.h"

namespace iris {

/// Throws iris::Error naming the file (and the line, for ASCII bodies and headers) on malformed
/// or truncated input; element counts are checked against the file size before allocating.
TriangleMesh readPly(const std::string& path);

/// The same, from file contents already in memory (`name` is used in messages).
TriangleMesh parsePly(const std::string& data, const std::string& name);

}  // namespace iris
