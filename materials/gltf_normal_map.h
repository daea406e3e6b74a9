// glTF 2.0 normal textures (§3.9.3 "Additional Textures", material.normalTextureInfo): a
// tangent-space normal map perturbs the shading normal of the glTF material it wraps.
//   scaledNormal = normalize((sample · 2 − 1) · (scale, scale, 1))       (schema material.normalTextureInfo, scale)
//   n' = normalize(x T + y B + z N),  B = (N × T) · w                   (§3.7.2.1 TANGENT: xyz, w = handedness)
// T and w are the TANGENT attribute (mesh attribute kTangentAttribute, already in the shape's
// space), interpolated and orthogonalised against N: the file's, or when the file has none the
// per-vertex tangents the importer generates as the spec asks (MikkTSpace's, from positions,
// normals and the normal texture's UVs; render/loader/gltf_tangents.h, docs/gltf.md says where
// they may differ from the reference implementation). Only a mesh with no usable attribute (not
// made by the glTF importer) falls back to ∂p/∂u of the hit triangle with w = 1. The texture is
// read linearly (not sRGB). The perturbed BSDF is iris's normal-map frame (materials/perturbed_frame.h)
// with flip_invalid_normals on and no shadowing term (glTF's BRDF has none).
#pragma once

#include "materials/gltf_texture.h"
#include "materials/material.h"

namespace iris::gltf {

/// The world-space tangent-space frame (T, B, N) at sp, as the comment above defines it.
struct TangentFrame {
    vec3 t, b, n;
};
TangentFrame tangentFrameAt(const ShadingPoint& sp);

/// The perturbed world-space normal at sp for the normal texture `map` with `scale`.
vec3 mappedNormal(const ShadingPoint& sp, const Texture& map, float scale);

/// `material` with its shading normal perturbed by `map` (a linear texture).
MaterialPtr makeNormalMapped(MaterialPtr material, TexturePtr map, float scale);

}  // namespace iris::gltf
