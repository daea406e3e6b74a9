// Shapes of a parsed scene: mesh files (obj, ply, serialized) and built-in shapes (sphere,
// rectangle, cube, disk) with their attached bsdf and area emitter.
#pragma once

#include "core/properties.h"
#include "render/scene_description.h"

namespace iris {

/// Build one shape from its <shape> Properties (meshes are transformed to world space).
ShapeDescription loadShape(const Properties& shape);

/// The material for a <bsdf> Properties, created once per Properties object (so every <ref> to
/// one id shares it). Types missing from MaterialRegistry give "file:line: bsdf type 'x' is not
/// supported yet (supported: ...)".
MaterialPtr materialFor(const Properties& bsdf);

}  // namespace iris
