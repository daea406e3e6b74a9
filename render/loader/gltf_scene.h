// The node walk of a glTF scene (§3.5): every node reachable from the default scene with its world
// matrix, and what it carries (mesh, camera, light).
#pragma once

#include <vector>

#include "core/math.h"
#include "render/loader/gltf_document.h"

namespace iris::gltf {

struct PlacedNode {
    int node = -1;
    mat4 world{1.0f};
};

/// The nodes of the default scene (`scene`, else scene 0, else every root node), depth first,
/// each with its world matrix. Cycles and out-of-range children are errors naming their path.
std::vector<PlacedNode> placeNodes(const Document& doc);

/// A node's local matrix: `matrix` (column-major) or T · R · S (§3.5.2; rotation a unit
/// quaternion x, y, z, w).
mat4 localMatrix(const Document& doc, int node);

}  // namespace iris::gltf
