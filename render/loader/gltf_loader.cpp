#include "render/loader/gltf_loader.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <map>

#include "core/memory_budget.h"
#include "render/film.h"
#include "render/integrator.h"
#include "render/lights/light.h"
#include "render/loader/gltf_material.h"
#include "render/loader/gltf_mesh.h"
#include "render/loader/gltf_scene.h"
#include "render/loader/gltf_tangents.h"
#include "render/sensors/sensor.h"
#include "render/scene_defaults.h"

namespace iris {

using gltf::Document;
using gltf::failAtPath;

namespace {

struct Primitive {
    TriangleMesh mesh;  // in the mesh's own space
    const gltf::ShapeMaterial* material;
};

void checkClosed(Document& doc, const Primitive& p);

/// Every triangle primitive of mesh `m`, read once. A primitive whose material has a normal
/// texture and whose file has no TANGENT gets generated tangents (§3.7.2.1: MikkTSpace's, from
/// the normal texture's UV set; render/loader/gltf_tangents.h); no other primitive pays for them.
std::vector<Primitive> readMesh(Document& doc, gltf::MaterialCache& materials, int m) {
    std::vector<Primitive> out;
    const tinygltf::Mesh& mesh = doc.model.meshes[size_t(m)];
    for (size_t p = 0; p < mesh.primitives.size(); ++p)
        if (std::optional<TriangleMesh> t = gltf::readPrimitive(doc, m, int(p))) {
            const gltf::ShapeMaterial& material = materials.material(mesh.primitives[p].material);
            if (material.normalMapped && !t->findAttribute(gltf::kTangentAttribute)) gltf::generateTangents(*t, material.normalTexCoord);
            out.push_back({std::move(*t), &material});
            checkClosed(doc, out.back());
        }
    return out;
}

ShapeDescription shapeOf(const Primitive& p, const mat4& toWorld, bool placed) {
    ShapeDescription s;
    auto mesh = std::make_shared<TriangleMesh>(p.mesh);
    if (placed) {
        mesh->transform(toWorld);
        gltf::transformTangents(*mesh, toWorld);
    }
    s.name = mesh->name;
    s.mesh = std::move(mesh);
    s.material = p.material->material;
    s.emission = p.material->emission;
    s.emissionTexture = p.material->emissionTexture;
    s.interior = p.material->interior;
    return s;
}

/// Meshes that are written out rather than instanced: a shape group holds no emitters, and the
/// TANGENT attribute a normal map reads (the file's or the generated one, so every normal-mapped
/// primitive) is placed with its mesh (an instance transforms only the hit's position, normals and
/// ∂p/∂u, render/instance_transform.cpp).
bool notInstanced(const std::vector<Primitive>& prims) {
    return std::any_of(prims.begin(), prims.end(), [](const Primitive& p) {
        return p.material->emission || p.material->emissionTexture ||
               (p.material->normalMapped && p.mesh.findAttribute(gltf::kTangentAttribute));
    });
}

/// KHR_materials_volume: "the mesh ... defines the boundaries of an homogeneous medium and
/// therefore must be manifold". An open one is rendered (rays may leave the medium through a
/// hole without crossing a boundary) with a warning.
void checkClosed(Document& doc, const Primitive& p) {
    if (!p.material->interior) return;
    if (const size_t open = openEdgeCount(p.mesh); open > 0)
        doc.warnings.push_back(strCat(p.mesh.name, ": KHR_materials_volume needs a closed mesh, but ", open,
                                      " edges belong to one triangle or to more than two"));
}

Properties plugin(const char* tag, const char* type, const Document& doc) { return Properties(tag, type, SourceLocation{doc.path, 0}); }

/// KHR_lights_punctual: point (candela), spot (candela; cones are half angles, as Mitsuba's),
/// directional (lux), each as radiometric values in iris's relative units; `range` is ignored.
std::shared_ptr<Light> lightOf(const Document& doc, int index, const mat4& world) {
    if (index < 0 || size_t(index) >= doc.model.lights.size())
        failAtPath(doc, "/extensions/KHR_lights_punctual/lights", "light ", index, " does not exist");
    const tinygltf::Light& l = doc.model.lights[size_t(index)];
    const std::string path = strCat("/extensions/KHR_lights_punctual/lights/", index);
    vec3 rgb(1.0f);
    if (l.color.size() == 3) rgb = vec3(l.color[0], l.color[1], l.color[2]);
    rgb *= float(l.intensity);
    if (!(rgb.x >= 0 && rgb.y >= 0 && rgb.z >= 0)) failAtPath(doc, path, "colour × intensity must be >= 0");
    const SourceLocation loc{doc.path, 0};
    Properties p;
    // glTF lights shine along the node's −z; Mitsuba's spot along +z: turn by 180° about x.
    const mat4 spotFrame = world * mat4(vec4(1, 0, 0, 0), vec4(0, -1, 0, 0), vec4(0, 0, -1, 0), vec4(0, 0, 0, 1));
    if (l.type == "point") {
        p = plugin("emitter", "point", doc);
        p.set("position", PointValue{vec3(world[3])}, loc);
        p.set("intensity", RGBValue{rgb}, loc);
    } else if (l.type == "spot") {
        p = plugin("emitter", "spot", doc);
        const float outer = glm::degrees(float(l.spot.outerConeAngle)), inner = glm::degrees(float(l.spot.innerConeAngle));
        if (!(outer > 0 && outer <= 90 && inner >= 0 && inner < outer)) failAtPath(doc, path + "/spot", "needs 0 <= innerConeAngle < outerConeAngle <= π/2");
        p.set("to_world", spotFrame, loc);
        p.set("cutoff_angle", outer, loc);
        p.set("beam_width", std::max(inner, 1e-3f), loc);
        p.set("intensity", RGBValue{rgb}, loc);
    } else if (l.type == "directional") {
        p = plugin("emitter", "directional", doc);
        p.set("direction", VectorValue{glm::normalize(vec3(world * vec4(0, 0, -1, 0)))}, loc);
        p.set("irradiance", RGBValue{rgb}, loc);
    } else {
        failAtPath(doc, path + "/type", "unknown light type '", l.type, "'");
    }
    return LightRegistry::instance().create(p);
}

int nodeLight(const tinygltf::Node& n) {
    const auto it = n.extensions.find("KHR_lights_punctual");
    if (it == n.extensions.end() || !it->second.IsObject() || !it->second.Has("light")) return -1;
    const tinygltf::Value& v = it->second.Get("light");
    return v.IsNumber() ? int(v.GetNumberAsDouble()) : -2;
}

/// Shapes, instances and lights of the document into `scene`.
void addContent(Document& doc, const mat4& toWorld, const std::string& rgbMode, SceneDescription& scene) {
    // One glTF unit in scene units (a volume's attenuationDistance): the cube root of to_world's volume scale.
    const float lengthScale = std::cbrt(std::abs(glm::determinant(mat3(toWorld))));
    if (!(lengthScale > 0) || !std::isfinite(lengthScale)) fail(doc.path, ": the transform placing the file is degenerate");
    gltf::MaterialCache materials(doc, rgbMode, lengthScale);
    const std::vector<gltf::PlacedNode> nodes = gltf::placeNodes(doc);
    std::map<int, int> uses;
    for (const gltf::PlacedNode& n : nodes)
        if (int m = doc.model.nodes[size_t(n.node)].mesh; m >= 0) ++uses[m];
    std::map<int, std::vector<Primitive>> meshes;
    std::map<int, std::shared_ptr<const ShapeGroupDescription>> groups;
    for (const gltf::PlacedNode& n : nodes) {
        const tinygltf::Node& node = doc.model.nodes[size_t(n.node)];
        const mat4 world = toWorld * n.world;
        if (int li = nodeLight(node); li != -1) scene.lights.push_back(lightOf(doc, li, world));
        if (node.mesh < 0) continue;
        if (size_t(node.mesh) >= doc.model.meshes.size()) failAtPath(doc, strCat("/nodes/", n.node, "/mesh"), "mesh ", node.mesh, " does not exist");
        auto it = meshes.find(node.mesh);
        if (it == meshes.end()) it = meshes.emplace(node.mesh, readMesh(doc, materials, node.mesh)).first;
        const std::vector<Primitive>& prims = it->second;
        if (uses[node.mesh] < 2 || notInstanced(prims)) {  // written out
            for (const Primitive& p : prims) scene.shapes.push_back(shapeOf(p, world, true));
            continue;
        }
        std::shared_ptr<const ShapeGroupDescription>& group = groups[node.mesh];
        if (!group) {
            auto g = std::make_shared<ShapeGroupDescription>();
            g->name = strCat(doc.path, ":/meshes/", node.mesh);
            for (const Primitive& p : prims) g->shapes.push_back(shapeOf(p, mat4(1.0f), false));
            group = std::move(g);
        }
        scene.instances.push_back({group, world, strCat(doc.path, ":/nodes/", n.node)});
    }
}

/// The camera node: the one named by `want` (node or camera name), else the first with a camera.
const gltf::PlacedNode* findCamera(const Document& doc, const std::vector<gltf::PlacedNode>& nodes, const std::string& want) {
    for (const gltf::PlacedNode& n : nodes) {
        const tinygltf::Node& node = doc.model.nodes[size_t(n.node)];
        if (node.camera < 0) continue;
        if (size_t(node.camera) >= doc.model.cameras.size()) failAtPath(doc, strCat("/nodes/", n.node, "/camera"), "camera ", node.camera, " does not exist");
        if (want.empty() || node.name == want || doc.model.cameras[size_t(node.camera)].name == want) return &n;
    }
    if (!want.empty()) fail(doc.path, ": no camera called '", want, "' (give a camera's or its node's name)");
    return nullptr;
}

/// Bounds of every shape's vertices (instances by their transformed group bounds' corners).
std::pair<vec3, vec3> sceneBounds(const SceneDescription& s) {
    vec3 lo(1e30f), hi(-1e30f);
    auto grow = [&](const TriangleMesh& m, const mat4& t) {
        for (const vec3& p : m.positions) {
            const vec3 w = vec3(t * vec4(p, 1.0f));
            lo = glm::min(lo, w), hi = glm::max(hi, w);
        }
    };
    for (const ShapeDescription& sh : s.shapes)
        if (sh.mesh) grow(*sh.mesh, mat4(1.0f));
    for (const InstanceDescription& i : s.instances)
        for (const ShapeDescription& sh : i.group->shapes)
            if (sh.mesh) grow(*sh.mesh, i.toWorld);
    if (lo.x > hi.x) lo = vec3(-1.0f), hi = vec3(1.0f);
    return {lo, hi};
}

void addCamera(const Document& doc, const GltfOptions& o, SceneDescription& scene) {
    const std::vector<gltf::PlacedNode> nodes = gltf::placeNodes(doc);
    const gltf::PlacedNode* cam = findCamera(doc, nodes, o.camera);
    float yfov = 0.6911f, aspect = 0.0f;  // 39.6°, Blender's default
    mat4 world;
    if (cam) {
        const int ci = doc.model.nodes[size_t(cam->node)].camera;
        const tinygltf::Camera& c = doc.model.cameras[size_t(ci)];
        if (c.type != "perspective") failAtPath(doc, strCat("/cameras/", ci, "/type"), "only perspective cameras are supported, not '", c.type, "'");
        yfov = float(c.perspective.yfov);
        aspect = float(c.perspective.aspectRatio);
        if (!(yfov > 0 && yfov < 3.1f)) failAtPath(doc, strCat("/cameras/", ci, "/perspective/yfov"), "must be in (0, π)");
        world = cam->world;
    } else {  // frame the scene's bounding sphere from +z (glTF's front)
        const auto [lo, hi] = sceneBounds(scene);
        const vec3 c = 0.5f * (lo + hi);
        const float r = std::max(0.5f * glm::length(hi - lo), 1e-3f);
        world = glm::translate(mat4(1.0f), c + vec3(0, 0, 1.1f * r / std::sin(0.5f * yfov)));
    }
    CameraDescription& cd = scene.camera;
    cd.width = o.width;
    cd.height = o.height > 0 ? o.height : aspect > 0 ? std::max(1, int(std::lround(o.width / aspect))) : o.width;
    chargeMemory(uint64_t(cd.width) * uint64_t(cd.height) * (Film::kStateBytesPerPixel + 9 * sizeof(float)), strCat("film of ", cd.width, "x", cd.height));
    // glTF cameras look along −z with +x right; Mitsuba's perspective looks along +z with +x left:
    // turn by 180° about y.
    const mat4 toWorld = world * mat4(vec4(-1, 0, 0, 0), vec4(0, 1, 0, 0), vec4(0, 0, -1, 0), vec4(0, 0, 0, 1));
    Properties p = plugin("sensor", "perspective", doc);
    const SourceLocation loc{doc.path, 0};
    p.set("to_world", toWorld, loc);
    p.set("fov", glm::degrees(yfov), loc);
    p.set("fov_axis", std::string("y"), loc);
    cd.sensor = SensorRegistry::instance().create(p, FilmSize{cd.width, cd.height});
}

void addEnvironment(const Document& doc, const GltfOptions& o, SceneDescription& scene) {
    const SourceLocation loc{doc.path, 0};
    if (!o.envmap.empty()) {
        Properties p = plugin("emitter", "envmap", doc);
        p.set("filename", std::filesystem::absolute(o.envmap).string(), loc);
        scene.lights.push_back(LightRegistry::instance().create(p));
        return;
    }
    const bool lit = !scene.lights.empty() || std::any_of(scene.shapes.begin(), scene.shapes.end(), [](const ShapeDescription& s) {
        return s.emission || s.emissionTexture;
    });
    if (!lit) scene.lights.push_back(LightRegistry::instance().create(plugin("emitter", "constant", doc)));  // radiance 1
}

}  // namespace

bool isGltfFile(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext == ".gltf" || ext == ".glb";
}

void appendGltf(const std::string& path, const mat4& toWorld, const std::string& rgbMode, SceneDescription& scene) {
    Document doc = gltf::readDocument(path);
    addContent(doc, toWorld, rgbMode, scene);
    for (const std::string& w : doc.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
}

namespace {

SceneDescription buildScene(const std::string& path, const GltfOptions& options, const std::function<Document()>& read) {
    if (!(options.width > 0 && options.width <= 65536 && options.height >= 0 && options.height <= 65536))
        fail(path, ": film size ", options.width, "x", options.height, " is out of range");
    MemoryAccount memory;
    SceneDescription scene;
    scene.sourceFile = path;
    Document doc = read();
    addContent(doc, mat4(1.0f), options.rgbMode, scene);
    addCamera(doc, options, scene);
    addEnvironment(doc, options, scene);
    // A KHR_materials_volume medium needs a volumetric integrator (the default one ignores media).
    scene.integrator = IntegratorRegistry::instance().create(Properties("integrator", scene.hasMedia() ? "volpath" : kDefaultIntegrator, {}));
    scene.spp = options.spp;
    for (const std::string& w : doc.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
    scene.memory = memory.take();
    return scene;
}

}  // namespace

SceneDescription loadGltfScene(const std::string& path, const GltfOptions& options) {
    return buildScene(path, options, [&] { return gltf::readDocument(path); });
}

SceneDescription loadGltfSceneFromMemory(const std::string& bytes, const std::string& name, const std::string& baseDir,
                                         const GltfOptions& options) {
    return buildScene(name, options, [&] { return gltf::readDocumentFromBytes(bytes, name, baseDir); });
}

}  // namespace iris
