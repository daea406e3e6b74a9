// Shapes of a parsed scene: the shape plugin its type names (ShapeRegistry, render/shapes/) with
// the attached bsdf and area emitter.
#pragma once

#include "core/properties.h"
#include "render/scene_description.h"

namespace iris {

/// Build one shape from its <shape> Properties (meshes are transformed to world space).
ShapeDescription loadShape(const Properties& shape);

/// The material for a <bsdf> Properties, created once per Properties object (so every <ref> to
/// one id shares it). Unknown types give "file:line: unknown bsdf type 'x' (supported: ...)".
MaterialPtr materialFor(const Properties& bsdf);

/// The medium for a <medium> Properties, created once per Properties object (MediumRegistry,
/// media/).
MediumPtr mediumFor(const Properties& medium);

}  // namespace iris
