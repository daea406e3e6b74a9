// Mitsuba's instancing shapes, `shapegroup` and `instance` (Mitsuba 3: src/render/shapegroup.cpp,
// src/shapes/shapegroup.cpp, src/shapes/instance.cpp). The loader handles them itself rather than
// through ShapeRegistry because a group holds whole shapes with their bsdfs (shape_loader).
#pragma once

#include "core/properties.h"
#include "render/scene_description.h"

namespace iris {

/// The group of a <shape type="shapegroup">, built once per Properties (every instance of one id
/// shares it). Its shapes may not be groups, instances or emitters (Mitsuba 3 refuses them).
std::shared_ptr<const ShapeGroupDescription> loadShapeGroup(const Properties& group);

/// A <shape type="instance">: exactly one shapegroup (a <ref>, unnamed or named "shapegroup", or
/// nested) and an optional to_world.
InstanceDescription loadInstance(const Properties& instance);

}  // namespace iris
