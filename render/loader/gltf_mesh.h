// glTF mesh primitives (glTF 2.0 §3.7.2) as iris triangle meshes: POSITION, NORMAL, TEXCOORD_0
// (uvs), TEXCOORD_1, COLOR_0 and TANGENT (mesh attributes named in materials/gltf_texture.h);
// TRIANGLES, TRIANGLE_STRIP and TRIANGLE_FAN (§3.7.2.1); points and lines are skipped.
#pragma once

#include <optional>

#include "core/mesh.h"
#include "render/loader/gltf_document.h"

namespace iris::gltf {

/// The triangles of primitive `p` of mesh `m` in the mesh's own space, or nothing for a
/// primitive without triangles (points, lines: returned empty with a warning in doc).
std::optional<TriangleMesh> readPrimitive(Document& doc, int m, int p);

/// The TANGENT attribute placed by `m` with its mesh (TriangleMesh::transform moves positions and
/// normals only): xyz as a direction (by m, renormalised), w · sign(det m) so that the bitangent
/// (N × T) · w follows the mirrored frame.
void transformTangents(TriangleMesh& mesh, const mat4& m);

}  // namespace iris::gltf
