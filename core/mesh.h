// Triangle mesh data as read from files (OBJ, PLY, Mitsuba .serialized) or generated
// (rectangle, cube, disk). Positions and normals are in object space until transformed.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/math.h"

namespace iris {

struct TriangleMesh {
    std::string name;                // for error messages (file name)
    std::vector<vec3> positions;
    std::vector<vec3> normals;       // per vertex, empty if none (face normals used)
    std::vector<vec2> uvs;           // per vertex, empty if none
    std::vector<uint32_t> indices;   // 3 per triangle

    size_t triangleCount() const { return indices.size() / 3; }
    /// Apply an affine transform to positions and normals (normals by the inverse transpose).
    void transform(const mat4& m);
    /// Reverse the winding and negate normals.
    void flipNormals();
    /// Throw iris::Error (naming `name`) if any index is out of range or a value is not finite.
    void validate() const;
};

/// Edges of the surface not shared by exactly two triangles, with vertices welded by exact
/// position (so split vertices at uv or normal seams do not open the surface): 0 for a closed,
/// manifold surface (the boundary a participating medium needs).
size_t openEdgeCount(const TriangleMesh& mesh);

/// Built-in shapes (Mitsuba conventions): rectangle [-1,1]² at z = 0 facing +z; cube [-1,1]³;
/// disk of radius 1 at z = 0 facing +z (tessellated with `segments` triangles).
TriangleMesh makeRectangle();
TriangleMesh makeCube();
TriangleMesh makeDisk(int segments = 256);

}  // namespace iris
