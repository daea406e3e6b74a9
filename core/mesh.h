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
    /// The uvs of triangle `tri`'s corners: its vertices' uvs, or (0, 0), (1, 0), (1, 1) for a mesh
    /// without uvs (Mitsuba's default triangle parametrisation).
    void cornerUVs(size_t tri, vec2 uv[3]) const {
        if (uvs.empty()) {
            uv[0] = vec2(0, 0), uv[1] = vec2(1, 0), uv[2] = vec2(1, 1);
            return;
        }
        for (int k = 0; k < 3; ++k) uv[k] = uvs[indices[3 * tri + k]];
    }
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
