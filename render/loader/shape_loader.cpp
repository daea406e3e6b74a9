#include "render/loader/shape_loader.h"

#include "core/io/obj_reader.h"
#include "core/io/ply_reader.h"
#include "core/io/serialized_reader.h"
#include "core/registry.h"
#include "spectral/spectrum_params.h"

namespace iris {

namespace {

std::string supportedList(const std::vector<std::string>& names) {
    std::string list;
    for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
    return list;
}

/// Mesh file errors name the file; add the scene line that asked for it.
template <typename F>
auto withLocation(const Properties& p, F&& f) {
    try {
        return f();
    } catch (const Error& e) {
        failAt(p.locationOf("filename"), e.what());
    }
}

/// Uniform scale factor of a transform's linear part, or an error for a non-uniform scale / shear.
float uniformScale(const mat4& m, const SourceLocation& loc) {
    const mat3 a(m);
    const float sx = glm::length(a[0]), sy = glm::length(a[1]), sz = glm::length(a[2]);
    const float tol = 1e-4f * std::max({sx, sy, sz});
    if (std::abs(sx - sy) > tol || std::abs(sx - sz) > tol || std::abs(glm::dot(a[0], a[1])) > tol * sx ||
        std::abs(glm::dot(a[0], a[2])) > tol * sx || std::abs(glm::dot(a[1], a[2])) > tol * sy)
        failAt(loc, "sphere: to_world must be a rotation, translation and uniform scale");
    if (!(sx > 0)) failAt(loc, "sphere: to_world has a zero scale");
    return sx;
}

void attachChildren(const Properties& p, ShapeDescription& s) {
    PropertiesPtr bsdf = p.getObject("bsdf", false);
    PropertiesPtr emitter = p.getObject("emitter", false);
    for (const PropertiesPtr& c : p.children()) {
        if (c->tag() == "bsdf") {
            if (bsdf) failAt(p.location(), "shape has more than one bsdf");
            bsdf = c;
        } else if (c->tag() == "emitter") {
            if (emitter) failAt(p.location(), "shape has more than one emitter");
            emitter = c;
        } else {
            failAt(c->location(), "<", c->tag(), "> is not supported inside a shape (supported: bsdf, emitter)");
        }
    }
    if (bsdf) {
        if (bsdf->tag() != "bsdf") failAt(p.locationOf("bsdf"), "parameter 'bsdf' must be a <bsdf>");
        s.material = materialFor(*bsdf);
    }
    if (emitter) {
        if (emitter->tag() != "emitter") failAt(p.locationOf("emitter"), "parameter 'emitter' must be an <emitter>");
        if (emitter->type() != "area")
            failAt(emitter->location(), "emitter type '", emitter->type(), "' cannot be attached to a shape (only 'area')");
        s.emission = getSpectrum(*emitter, "radiance", SpectrumKind::Illuminant);
        emitter->checkUnqueried();
    }
}

}  // namespace

MaterialPtr materialFor(const Properties& bsdf) {
    if (bsdf.instance) return std::static_pointer_cast<const Material>(bsdf.instance);
    const MaterialRegistry& reg = MaterialRegistry::instance();
    if (!reg.has(bsdf.type()))
        failAt(bsdf.location(), "bsdf type '", bsdf.type(), "' is not supported yet (supported: ", supportedList(reg.names()), ")");
    MaterialPtr m = reg.create(bsdf);
    bsdf.instance = std::const_pointer_cast<Material>(m);
    return m;
}

ShapeDescription loadShape(const Properties& p) {
    ShapeDescription s;
    const std::string& type = p.type();
    s.name = !p.id().empty() ? p.id() : type;
    const mat4 toWorld = p.getTransform("to_world");
    const bool flip = p.getBool("flip_normals", false);
    TriangleMesh mesh;
    bool isMesh = true;
    if (type == "obj") {
        mesh = withLocation(p, [&] { return readObj(p.getString("filename")); });
        if (!p.getBool("flip_tex_coords", true))  // the reader flips v like Mitsuba; undo on request
            for (vec2& uv : mesh.uvs) uv.y = 1.0f - uv.y;
    } else if (type == "ply") {
        mesh = withLocation(p, [&] { return readPly(p.getString("filename")); });
    } else if (type == "serialized") {
        const int index = p.getInt("shape_index", 0);
        SerializedMesh sm = withLocation(p, [&] { return readSerialized(p.getString("filename"), index); });
        mesh = std::move(sm.mesh);
        s.faceNormals = sm.faceNormals;
    } else if (type == "rectangle") {
        mesh = makeRectangle();
    } else if (type == "cube") {
        mesh = makeCube();
    } else if (type == "disk") {
        mesh = makeDisk();
    } else if (type == "sphere") {
        isMesh = false;
        s.type = ShapeDescription::Type::Sphere;
        const vec3 c = p.getPoint("center", vec3(0.0f));
        const float r = p.getFloat("radius", 1.0f);
        if (!(r > 0)) failAt(p.locationOf("radius"), "sphere radius must be positive");
        s.center = transformPoint(toWorld, c);
        s.radius = r * uniformScale(toWorld, p.locationOf("to_world"));
        s.flipNormals = flip;
    } else {
        failAt(p.location(), "shape type '", type, "' is not supported (supported: obj, ply, serialized, sphere, rectangle, cube, disk)");
    }
    if (p.id().empty() && p.has("filename") && isMesh) s.name = p.getString("filename");
    if (isMesh) {
        mesh.transform(toWorld);
        if (flip) mesh.flipNormals();
        if (!p.id().empty()) mesh.name = p.id() + " (" + mesh.name + ")";
        s.faceNormals = p.getBool("face_normals", s.faceNormals);
        if (s.faceNormals) mesh.normals.clear();
        s.mesh = std::make_shared<TriangleMesh>(std::move(mesh));
    }
    attachChildren(p, s);
    p.checkUnqueried();
    return s;
}

}  // namespace iris
