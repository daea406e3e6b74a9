// Load-time check of mesh_attribute textures against the shape they are on (declared in
// mesh_attribute.h): every mesh_attribute in a shape's bsdf tree must name an attribute of that
// shape's mesh with a usable number of channels, so that rendering never meets a lookup it cannot
// serve (Mitsuba 3 throws "Invalid attribute requested" at the first lookup instead).
#include "materials/textures/mesh_attribute.h"

namespace iris {
namespace {

std::string attributeList(const TriangleMesh& mesh) {
    if (mesh.attributes.empty()) return "it has none";
    std::string names;
    for (const MeshAttribute& a : mesh.attributes) names += (names.empty() ? "" : ", ") + a.name;
    return "it has " + names;
}

void checkTexture(const Properties& tex, const TriangleMesh* mesh, const std::string& owner) {
    const Properties::Entry* e = tex.find("name");
    const std::string* name = e ? std::get_if<std::string>(&e->value) : nullptr;
    if (!name) return;  // the texture's factory reports a missing or mistyped name
    const SourceLocation& loc = tex.location();
    if (!mesh) failAt(loc, "mesh_attribute '", *name, "' on ", owner, ", which has no mesh attributes");
    const MeshAttribute* a = mesh->findAttribute(*name);
    if (!a) failAt(loc, "mesh_attribute '", *name, "': ", owner, " has no such attribute (", attributeList(*mesh), ")");
    const auto use = tex.objectCache() ? tex.objectCache()->find<MeshAttributeUse>(tex) : nullptr;  // set by the factory
    if (use && use->asFloat && a->channels != 1)
        failAt(loc, "mesh_attribute '", *name, "' of ", owner, " has ", a->channels,
               " channels, but a float parameter needs 1 (Mitsuba 3's eval_attribute_1 refuses other sizes too)");
    if (a->channels != 1 && a->channels != 3)
        failAt(loc, "mesh_attribute '", *name, "' of ", owner, " has ", a->channels, " channels; a texture reads 1 or 3");
}

}  // namespace

void checkMeshAttributes(const Properties& tree, const TriangleMesh* mesh, const std::string& owner) {
    if (tree.tag() == "texture" && tree.type() == "mesh_attribute") checkTexture(tree, mesh, owner);
    for (const std::string& n : tree.names())
        if (const PropertiesPtr* nested = tree.peekObject(n)) checkMeshAttributes(**nested, mesh, owner);
    for (const PropertiesPtr& child : tree.children()) checkMeshAttributes(*child, mesh, owner);
}

}  // namespace iris
