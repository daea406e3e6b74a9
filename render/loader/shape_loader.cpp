#include "render/loader/shape_loader.h"

#include <tuple>

#include "core/mesh.h"
#include "media/volume_light.h"
#include "materials/textures/mesh_attribute.h"
#include "materials/textures/texture_params.h"
#include "render/shapes/shape.h"
#include "spectral/spectrum_params.h"

namespace iris {

namespace {

/// A shape's bsdf and area emitter, named (`<ref name="bsdf" .../>`) or nested without a name.
struct ShapeChildren {
    PropertiesPtr bsdf, emitter, interior, exterior;
};

ShapeChildren readChildren(const Properties& p) {
    ShapeChildren c{p.getObject("bsdf", false), p.getObject("emitter", false), p.getObject("interior", false),
                    p.getObject("exterior", false)};
    for (const PropertiesPtr& child : p.children()) {
        if (child->tag() == "bsdf") {
            if (c.bsdf) failAt(p.location(), "shape has more than one bsdf");
            c.bsdf = child;
        } else if (child->tag() == "emitter") {
            if (c.emitter) failAt(p.location(), "shape has more than one emitter");
            c.emitter = child;
        } else {
            failAt(child->location(), "<", child->tag(), "> is not supported inside a shape (supported: bsdf, emitter, and "
                   "<medium name=\"interior\"> / <medium name=\"exterior\">)");
        }
    }
    return c;
}

/// A medium needs a boundary that separates its inside from the rest (Mitsuba: "interior" is the
/// side the normals point away from): spheres are closed, cylinders (no caps) are not; a mesh must have every edge shared by
/// exactly two triangles, with vertices welded by position (so that uv seams do not count); an
/// sdfgrid's surface is closed when it stays inside the grid (every sample on the grid's faces > 0).
void checkClosedBoundary(const Properties& p, const ShapeDescription& s) {
    if (s.type == ShapeDescription::Type::SdfGrid && !s.sdf->closed)
        failAt(p.locationOf("interior"), "shape '", s.name, "' has an interior medium but its sdfgrid surface reaches the "
               "grid's boundary (a sample on a face of the grid is <= 0), so it is not closed: a medium needs a closed boundary");
    if (s.type == ShapeDescription::Type::Cylinder)
        failAt(p.locationOf("interior"), "shape '", s.name, "' has an interior medium but a cylinder has no end caps: a "
               "medium needs a closed boundary (use a closed mesh, obj or ply, or a sphere)");
    if (s.type != ShapeDescription::Type::Mesh || !s.mesh) return;
    const size_t open = openEdgeCount(*s.mesh);
    if (open > 0)
        failAt(p.locationOf("interior"), "shape '", s.name, "' has an interior medium but is not a closed surface (", open,
               " edges belong to one triangle, or to more than two): a medium needs a closed boundary");
}

/// "a sphere", "a cylinder" or "an sdfgrid", for messages about shapes that are not meshes.
const char* analyticTypeName(ShapeDescription::Type t) {
    return t == ShapeDescription::Type::Sphere ? "a sphere" : t == ShapeDescription::Type::Cylinder ? "a cylinder" : "an sdfgrid";
}

/// The mesh_attribute textures of the shape's bsdf or emitter must name attributes of its mesh
/// (checked here, per shape, because one bsdf may serve several shapes); spheres, cylinders and
/// sdf grids have none.
void checkAttributes(const Properties& tree, const ShapeDescription& s) {
    if (s.type == ShapeDescription::Type::Mesh)
        checkMeshAttributes(tree, s.mesh.get(), strCat("shape '", s.name, "'"));
    else
        checkMeshAttributes(tree, nullptr, strCat("shape '", s.name, "' (", analyticTypeName(s.type), ")"));
}

/// A shape's <emitter type="volumelight"> makes its interior medium emit (Mitsuba 3: the emitter
/// is given to the shape's interior medium, Medium::set_emitter); the shape itself does not.
void attachVolumeLight(const Properties& p, const ShapeChildren& c) {
    if (!c.interior)
        failAt(c.emitter->location(), "a volumelight needs a shape with an interior medium, which it makes emit");
    if (c.interior->tag() != "medium") failAt(p.locationOf("interior"), "parameter 'interior' must be a <medium>");
    // The cache holds the medium itself (mutable while the scene loads), mediumFor a const view of it.
    std::const_pointer_cast<Medium>(mediumFor(*c.interior))->setEmission(readVolumeLight(*c.emitter), c.emitter->location());
}

void attachChildren(const Properties& p, const ShapeChildren& c, ShapeDescription& s) {
    if (c.bsdf) {
        if (c.bsdf->tag() != "bsdf") failAt(p.locationOf("bsdf"), "parameter 'bsdf' must be a <bsdf>");
        s.material = materialFor(*c.bsdf);
        checkAttributes(*c.bsdf, s);
    }
    if (c.emitter && c.emitter->type() == "volumelight") {
        attachVolumeLight(p, c);
    } else if (c.emitter) {
        if (c.emitter->tag() != "emitter") failAt(p.locationOf("emitter"), "parameter 'emitter' must be an <emitter>");
        if (s.type == ShapeDescription::Type::SdfGrid)
            failAt(c.emitter->location(), "an sdfgrid cannot be an area emitter (Mitsuba 3 does not allow it either)");
        if (c.emitter->type() != "area")
            failAt(c.emitter->location(), "emitter type '", c.emitter->type(), "' cannot be attached to a shape (only 'area' and 'volumelight')");
        const PropertiesPtr* radiance = c.emitter->peekObject("radiance");
        if (radiance && (*radiance)->tag() == "texture") {  // Mitsuba: a texture over the shape's uv (D65-lit in spectral mode)
            s.emissionTexture = getSpectrumTexture(*c.emitter, "radiance", SpectrumKind::Illuminant);
            checkAttributes(**radiance, s);
        } else
            s.emission = getSpectrum(*c.emitter, "radiance", SpectrumKind::Illuminant);
        c.emitter->checkUnqueried();
    }
    for (const auto& [name, obj, slot] : {std::tuple{"interior", c.interior, &s.interior}, std::tuple{"exterior", c.exterior, &s.exterior}}) {
        if (!obj) continue;
        if (obj->tag() != "medium") failAt(p.locationOf(name), "parameter '", name, "' must be a <medium>");
        *slot = mediumFor(*obj);
    }
    if (s.interior) checkClosedBoundary(p, s);
}

}  // namespace

MediumPtr mediumFor(const Properties& medium) {
    return cachedObject<Medium>(medium, [&] { return std::const_pointer_cast<Medium>(MediumRegistry::instance().create(medium)); });
}

MaterialPtr materialFor(const Properties& bsdf) {
    return cachedObject<Material>(bsdf, [&] { return std::const_pointer_cast<Material>(MaterialRegistry::instance().create(bsdf)); });
}

ShapeDescription loadShape(const Properties& p) {
    const ShapeChildren children = readChildren(p);
    ShapeDescription s = *ShapeRegistry::instance().create(p);
    attachChildren(p, children, s);
    return s;
}

}  // namespace iris
