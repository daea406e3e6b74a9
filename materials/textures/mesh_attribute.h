// The `mesh_attribute` texture (Mitsuba 3, src/textures/mesh_attribute.cpp): a triangle mesh's
// per-vertex or per-face attribute (core/mesh.h MeshAttribute, e.g. a PLY file's vertex colours)
// read at the hit (a material's lookups, an area emitter's radiance at a hit or a light sample).
// Its needs are checked when the scene loads, per shape, by checkMeshAttributes (the shape loader
// calls it with the shape's bsdf and emitter), so a scene never renders a lookup that cannot be
// served; such a lookup (a query without a mesh or without the attribute, only possible from code)
// gives 0.
#pragma once

#include <string>

#include "core/mesh.h"
#include "core/properties.h"

namespace iris {

/// What a created mesh_attribute texture needs, recorded on its Properties (`instance`) by the
/// factory: the attribute's name and whether some material reads it as a float (1 channel needed;
/// as a spectrum 1 or 3 channels do).
struct MeshAttributeUse {
    std::string name;
    bool asFloat = false;
};

/// Throws "file:line: ..." (the texture's line) for the first mesh_attribute texture in `tree`
/// (an object and everything nested in or referenced by it) that `mesh` cannot serve: a missing
/// attribute, or one with the wrong number of channels. `mesh` nullptr means no mesh attributes
/// exist there; `owner` names the place in the messages ("shape 'a.ply'", "shape 'ball', a sphere").
void checkMeshAttributes(const Properties& tree, const TriangleMesh* mesh, const std::string& owner);

}  // namespace iris
