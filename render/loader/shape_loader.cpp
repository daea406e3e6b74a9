#include "render/loader/shape_loader.h"

#include "render/shapes/shape.h"
#include "spectral/spectrum_params.h"

namespace iris {

namespace {

/// A shape's bsdf and area emitter, named (`<ref name="bsdf" .../>`) or nested without a name.
struct ShapeChildren {
    PropertiesPtr bsdf, emitter;
};

ShapeChildren readChildren(const Properties& p) {
    ShapeChildren c{p.getObject("bsdf", false), p.getObject("emitter", false)};
    for (const PropertiesPtr& child : p.children()) {
        if (child->tag() == "bsdf") {
            if (c.bsdf) failAt(p.location(), "shape has more than one bsdf");
            c.bsdf = child;
        } else if (child->tag() == "emitter") {
            if (c.emitter) failAt(p.location(), "shape has more than one emitter");
            c.emitter = child;
        } else {
            failAt(child->location(), "<", child->tag(), "> is not supported inside a shape (supported: bsdf, emitter)");
        }
    }
    return c;
}

void attachChildren(const Properties& p, const ShapeChildren& c, ShapeDescription& s) {
    if (c.bsdf) {
        if (c.bsdf->tag() != "bsdf") failAt(p.locationOf("bsdf"), "parameter 'bsdf' must be a <bsdf>");
        s.material = materialFor(*c.bsdf);
    }
    if (c.emitter) {
        if (c.emitter->tag() != "emitter") failAt(p.locationOf("emitter"), "parameter 'emitter' must be an <emitter>");
        if (c.emitter->type() != "area")
            failAt(c.emitter->location(), "emitter type '", c.emitter->type(), "' cannot be attached to a shape (only 'area')");
        s.emission = getSpectrum(*c.emitter, "radiance", SpectrumKind::Illuminant);
        c.emitter->checkUnqueried();
    }
}

}  // namespace

MaterialPtr materialFor(const Properties& bsdf) {
    if (bsdf.instance) return std::static_pointer_cast<const Material>(bsdf.instance);
    MaterialPtr m = MaterialRegistry::instance().create(bsdf);
    bsdf.instance = std::const_pointer_cast<Material>(m);
    return m;
}

ShapeDescription loadShape(const Properties& p) {
    const ShapeChildren children = readChildren(p);
    ShapeDescription s = *ShapeRegistry::instance().create(p);
    attachChildren(p, children, s);
    return s;
}

}  // namespace iris
