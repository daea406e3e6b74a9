// Mitsuba ".serialized" meshes (format versions 3 and 4). Layout (little endian):
//   per shape: uint16 0x041C, uint16 version, then one zlib stream holding
//     uint32 flags (0x1 normals, 0x2 uvs, 0x8 colours, 0x10 face normals, 0x1000 float, 0x2000 double),
//     [v4: NUL-terminated name], uint64 vertexCount, uint64 triangleCount,
//     positions, [normals], [uvs], [colours] (float or double), indices (uint32, or uint64 when
//     vertexCount > 2^32 − 1);
//   at the end: one offset per shape (uint32 in v3, uint64 in v4) and a uint32 shape count.
#pragma once

#include <string>

#include "core/mesh.h"

namespace iris {

struct SerializedMesh {
    TriangleMesh mesh;
    bool faceNormals = false;  // the file asks for flat shading
};

/// Read shape `shapeIndex` of a .serialized file (vertex colours are skipped). Throws iris::Error
/// naming the file for bad indices, malformed, truncated or absurd data (counts are checked
/// against the compressed size times zlib's maximum ratio before allocating).
SerializedMesh readSerialized(const std::string& path, int shapeIndex);

/// Number of shapes in a .serialized file.
int serializedShapeCount(const std::string& path);

}  // namespace iris
