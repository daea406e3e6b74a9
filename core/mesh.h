// Triangle mesh data as read from files (OBJ, PLY, Mitsuba .serialized) or generated
// (rectangle, cube, disk). Positions and normals are in object space until transformed.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/math.h"

namespace iris {

struct TriangleMesh;

/// A named per-vertex or per-face quantity of a mesh (Mitsuba 3's mesh attributes, src/render/mesh.cpp
/// add_attribute): `name` starts with "vertex_" (one value per vertex, interpolated with the hit's
/// barycentrics) or "face_" (one value per triangle, constant over it); `channels` floats per
/// element (PLY colours: 3, other properties: 1 to 4), stored element after element.
struct MeshAttribute {
    std::string name;
    int channels = 1;
    std::vector<float> values;

    bool perFace() const { return name.rfind("face_", 0) == 0; }
    /// The elements whose values make up the attribute on triangle `tri` at the barycentrics
    /// b = (b1, b2), and their weights: the triangle's three vertices with (1 − b1 − b2, b1, b2)
    /// (the hit point's interpolation, render/scene.cpp), or its face with weight 1. Returns how many.
    int elements(const TriangleMesh& mesh, size_t tri, vec2 b, size_t element[3], float weight[3]) const;
    float value(size_t element, int channel) const { return values[element * size_t(channels) + size_t(channel)]; }
    /// Channel `c` on triangle `tri` at barycentrics b (the weighted sum of elements()).
    float at(const TriangleMesh& mesh, size_t tri, vec2 b, int c) const;
};

struct TriangleMesh {
    std::string name;                // for error messages (file name)
    std::vector<vec3> positions;
    std::vector<vec3> normals;       // per vertex, empty if none (face normals used)
    std::vector<vec2> uvs;           // per vertex, empty if none
    std::vector<uint32_t> indices;   // 3 per triangle
    std::vector<MeshAttribute> attributes;  // extra per-vertex / per-face data (PLY), usually none

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
    /// The attribute called `name`, or nullptr.
    const MeshAttribute* findAttribute(const std::string& name) const {
        for (const MeshAttribute& a : attributes)
            if (a.name == name) return &a;
        return nullptr;
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
