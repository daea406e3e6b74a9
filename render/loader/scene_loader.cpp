#include "render/loader/scene_loader.h"

#include "core/memory_budget.h"
#include "core/xml/xml_parser.h"
#include "materials/textures/mesh_attribute.h"
#include "render/film.h"
#include "render/films/film_description.h"
#include "render/integrator.h"
#include "render/lights/light.h"
#include "render/loader/gltf_loader.h"
#include "render/loader/instance_loader.h"
#include "render/loader/scene_upgrade.h"
#include "render/loader/shape_loader.h"
#include "render/samplers/sampler_description.h"
#include "render/sensors/sensor.h"

namespace iris {

namespace {

/// A sensor's film and sampler, named or nested without a name (Mitsuba: one of each).
struct SensorChildren {
    PropertiesPtr film, sampler, medium;
};

SensorChildren readSensorChildren(const Properties& p) {
    SensorChildren c{p.getObject("film", false), p.getObject("sampler", false), p.getObject("medium", false)};
    for (const PropertiesPtr& child : p.children()) {
        if (child->tag() != "film" && child->tag() != "sampler" && child->tag() != "medium")
            failAt(child->location(), "unexpected <", child->tag(), "> inside <sensor> (allowed: film, sampler, medium)");
        PropertiesPtr& slot = child->tag() == "film" ? c.film : child->tag() == "sampler" ? c.sampler : c.medium;
        if (slot) failAt(child->location(), "sensor has more than one <", child->tag(), ">");
        slot = child;
    }
    return c;
}

/// The sensor plugin, bound to its film's size; the film plugin and the sampler plugin (its sample
/// count and sequence). upgradeScene gave a sensor without them the defaults
/// (render/scene_defaults.h).
void loadSensor(const Properties& p, SceneDescription& scene) {
    const SensorChildren c = readSensorChildren(p);
    if (!c.film || !c.sampler) failAt(p.location(), "internal error: the sensor has no film or sampler (upgradeScene fills them)");
    const FilmDescription film = *FilmRegistry::instance().create(*c.film);
    // The film's sums and the three 3-channel float images written from them (EXR, mean, LDR).
    const uint64_t pixels = uint64_t(film.width) * uint64_t(film.height);
    withLocation(p.location(), [&] {
        chargeMemory(pixels * (Film::kStateBytesPerPixel + 9 * sizeof(float)), strCat("film of ", film.width, "x", film.height, " pixels"));
    });
    CameraDescription& cam = scene.camera;
    cam.width = film.width;
    cam.height = film.height;
    cam.filter = film.filter;
    cam.ldr = film.ldr;
    cam.sensor = SensorRegistry::instance().create(p, FilmSize{film.width, film.height});
    if (c.medium) {
        if (c.medium->tag() != "medium") failAt(p.locationOf("medium"), "parameter 'medium' must be a <medium>");
        cam.medium = mediumFor(*c.medium);
    }
    const std::shared_ptr<SamplerDescription> sampler = SamplerRegistry::instance().create(*c.sampler);
    scene.spp = sampler->sampleCount;
    scene.samplerName = c.sampler->type();
    scene.samplePattern = sampler->pattern;
}

void loadEmitter(const Properties& p, SceneDescription& scene) {
    if (p.type() == "area") {
        // Area emitters are attached to shapes; a top-level one only makes sense with an id to <ref>.
        if (p.id().empty()) failAt(p.location(), "an area emitter must be inside a <shape> (or have an id and be referenced from one)");
        return;
    }
    scene.lights.push_back(LightRegistry::instance().create(p));
    checkMeshAttributes(p, nullptr, strCat("the ", p.type(), " emitter (not on a shape)"));  // e.g. a spot's texture
}

/// <shape type="gltf" filename="..."> with optional to_world and rgb_mode (render/loader/gltf_loader.h).
void loadGltfShape(const Properties& p, SceneDescription& scene) {
    const std::string file = p.getString("filename");
    const mat4 toWorld = p.getTransform("to_world");
    const std::string rgbMode = p.getString("rgb_mode", "point");
    p.checkUnqueried();
    withLocation(p.locationOf("filename"), [&] { appendGltf(file, toWorld, rgbMode, scene); });
}

void loadObject(const Properties& p, SceneDescription& scene, bool& haveSensor, bool& haveIntegrator) {
    const std::string& tag = p.tag();
    if (tag == "shape" && p.type() == "shapegroup") {
        loadShapeGroup(p);  // created now so that its errors show even when no instance uses it; not rendered itself
    } else if (tag == "shape" && p.type() == "gltf") {
        loadGltfShape(p, scene);  // docs/gltf.md: a glTF file's meshes and lights placed in the scene
    } else if (tag == "shape" && p.type() == "instance") {
        scene.instances.push_back(loadInstance(p));
    } else if (tag == "shape") {
        scene.shapes.push_back(loadShape(p));
    } else if (tag == "bsdf") {
        materialFor(p);  // created now so that its errors show even when unused
    } else if (tag == "texture") {
        // Built by the material that uses it (which knows the spectrum kind).
    } else if (tag == "emitter") {
        loadEmitter(p, scene);
    } else if (tag == "sensor") {
        if (haveSensor) failAt(p.location(), "only one <sensor> is supported");
        haveSensor = true;
        loadSensor(p, scene);
    } else if (tag == "integrator") {
        if (haveIntegrator) failAt(p.location(), "only one <integrator> is supported");
        haveIntegrator = true;
        scene.integrator = IntegratorRegistry::instance().create(p);
    } else if (tag == "sampler" || tag == "film" || tag == "rfilter") {
        failAt(p.location(), "<", tag, "> must be inside a <sensor>");
    } else if (tag == "medium") {
        mediumFor(p);  // created now so that its errors show; checkMediaHaveBoundaries finds unused ones
    } else if (tag == "phase") {
        failAt(p.location(), "a <phase> belongs inside a <medium>");
    } else {
        failAt(p.location(), "<", tag, "> is not supported yet");
    }
}

/// A top-level <medium> that no shape (interior/exterior) and no sensor refers to has no boundary
/// and would be silently ignored (Mitsuba ignores it too); iris refuses it.
void checkMediaHaveBoundaries(const ParsedScene& parsed, const SceneDescription& scene, std::vector<std::string>& problems) {
    std::vector<const void*> used{scene.camera.medium.get()};
    for (const ShapeDescription& s : scene.shapes) used.insert(used.end(), {s.interior.get(), s.exterior.get()});
    for (const InstanceDescription& i : scene.instances)
        for (const ShapeDescription& s : i.group->shapes) used.insert(used.end(), {s.interior.get(), s.exterior.get()});
    for (const PropertiesPtr& obj : parsed.objects) {
        const std::shared_ptr<Medium> made = obj->objectCache() ? obj->objectCache()->find<Medium>(*obj) : nullptr;
        if (obj->tag() == "medium" && made && std::find(used.begin(), used.end(), made.get()) == used.end())
            problems.push_back(strCat(obj->location().str(), ": <medium id=\"", obj->id(), "\"> has no boundary: no shape refers to it as "
                                      "'interior' or 'exterior' and the sensor is not inside it"));
    }
}

/// Every top-level object is loaded even after one fails, so that a file with several problems
/// reports all of them at once: one iris::Error whose lines are the "file:line: problem" messages.
SceneDescription build(ParsedScene parsed) {
    upgradeScene(parsed);  // version rules and defaults, before any plugin reads (render/loader/scene_upgrade.h)
    MemoryAccount memory;  // the meshes, textures and film this scene holds (core/memory_budget.h)
    SceneDescription scene;
    scene.sourceFile = parsed.sourceFile;
    bool haveSensor = false, haveIntegrator = false;
    std::vector<std::string> problems;
    auto attempt = [&](auto&& load) {
        try {
            load();
        } catch (const Error& e) {
            // A shapegroup's problem shows once, not again for each instance that uses it.
            if (std::find(problems.begin(), problems.end(), e.what()) == problems.end()) problems.emplace_back(e.what());
        }
    };
    for (const PropertiesPtr& obj : parsed.objects)
        attempt([&] { loadObject(*obj, scene, haveSensor, haveIntegrator); });
    checkMediaHaveBoundaries(parsed, scene, problems);
    if (problems.empty() && scene.hasMedia() && !scene.integrator->rendersMedia())
        problems.push_back(strCat(scene.sourceFile, ": the scene has participating media, which integrator '", scene.integrator->type(),
                                  "' ignores: use 'volpath' or 'volpathmis'"));
    if (!problems.empty()) {
        std::string all;
        for (const std::string& m : problems) all += (all.empty() ? "" : "\n") + m;
        fail(all);
    }
    scene.memory = memory.take();
    return scene;
}

}  // namespace

// The parser charges what the parsed tree holds (core/xml/xml_parser.cpp); `parsing` collects it and
// gives it back once the scene has been built from the tree (build's own account keeps what the
// scene holds).
SceneDescription loadScene(const std::string& path, const std::map<std::string, std::string>& defines) {
    MemoryAccount parsing;
    return build(parseSceneFile(path, defines));
}

SceneDescription loadSceneFromString(const std::string& xml, const std::string& baseDir,
                                     const std::map<std::string, std::string>& defines) {
    MemoryAccount parsing;
    return build(parseSceneString(xml, baseDir, defines));
}

}  // namespace iris
