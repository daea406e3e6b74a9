// Shape plugins: every <shape> type registers a factory in ShapeRegistry that builds its geometry
// (ShapeDescription); the scene loader (render/loader/shape_loader) then attaches the shape's
// bsdf and area emitter, which are the same for every shape type.
#pragma once

#include "core/registry.h"
#include "render/scene_description.h"

namespace iris {

using ShapeRegistry = Registry<ShapeDescription>;

/// The part every triangle-mesh shape shares: to_world (into world space), flip_normals,
/// face_normals (default `faceNormals`, e.g. from a serialized file) and the shape's name.
std::shared_ptr<ShapeDescription> meshShape(const Properties& p, TriangleMesh mesh, bool faceNormals = false);

/// The uniform scale factor of a transform's linear part (rotation × uniform scale), or an error at
/// `loc` naming `plugin` for a non-uniform scale, a shear or a zero scale: the analytic shapes
/// (sphere, cylinder) stay what they are only under such transforms (Mitsuba: "non-uniform scales
/// are not permitted").
float uniformScale(const mat4& m, const SourceLocation& loc, const std::string& plugin);

}  // namespace iris
