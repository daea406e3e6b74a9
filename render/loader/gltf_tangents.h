// Per-vertex tangents for a glTF primitive whose material has a normal texture but whose file has
// no TANGENT attribute. glTF 2.0 §3.7.2.1 ("Meshes", TANGENT) and material.normalTextureInfo: "When
// tangents are not specified, client implementations SHOULD calculate tangents using default
// MikkTSpace algorithms with the specified vertex positions, normals, and texture coordinates
// associated with the normal texture." Written from the published description (M. Mikkelsen,
// "Simulation of Wrinkled Surfaces Revisited", MSc thesis, 2008), not from mikktspace.c:
//   * per triangle, ∂p/∂u and ∂p/∂v from the UV derivatives; triangles with a zero UV (or position)
//     area are degenerate and contribute nothing;
//   * per corner, both projected onto the plane of that corner's vertex normal, normalised and
//     weighted by the corner angle;
//   * summed over the corners of a "welded" vertex: same position, normal and UV bit for bit AND the
//     same orientation (sign of the UV Jacobian), so a mirrored UV island is kept apart and gets
//     w = −1;
//   * T = normalize(ΣT), w = sign(dot(N × T, ΣB)) (§3.7.2.1: bitangent = cross(N, T) · w).
// glTF's normal textures are +X right, +Y up in the image (§3.9.3, normalTexture) with UV (0, 0)
// at the image's upper-left corner (§3.8 "Textures", images), so the bitangent B that a texel's
// green channel moves along is −∂p/∂v: MikkTSpace on (u, 1 − v), as glTF importers that flip v
// (Blender's) run it. A vertex with no usable corner gets a tangent
// orthogonal to its normal chosen deterministically (Frame::fromNormal), w = 1.
#pragma once

#include "core/mesh.h"

namespace iris::gltf {

/// Adds the mesh attribute kTangentAttribute (xyz, w; materials/gltf_texture.h) to `mesh` from its
/// positions, normals (face normals when it has none) and UV set `texCoord` (0: mesh.uvs, 1: the
/// attribute kTexCoord1Attribute; a missing set counts as degenerate). A vertex whose corners need
/// different tangents (corners of both orientations at a mirror seam, or of different faces of a
/// mesh without normals) is split: a copy with every per-vertex datum is appended and those
/// corners' indices point to it.
void generateTangents(TriangleMesh& mesh, int texCoord);

}  // namespace iris::gltf
