#include "render/loader/scene_loader.h"

#include "render/loader/shape_loader.h"
#include "core/xml/xml_parser.h"
#include "core/registry.h"
#include "render/lights/light.h"

namespace iris {

namespace {

constexpr int kMaxFilmSide = 1 << 16;
constexpr int64_t kMaxFilmPixels = int64_t(1) << 28;
constexpr int kMaxSamples = 1 << 24;

void loadIntegrator(const Properties& p, IntegratorDescription& d) {
    // Mitsuba 3's `moment` wraps one integrator and adds its per-pixel first and second moments as
    // AOVs; iris's film always keeps both (render --variance writes them), so it renders the inner one.
    if (p.type() == "moment") {
        if (p.children().size() != 1 || p.children()[0]->tag() != "integrator")
            failAt(p.location(), "integrator 'moment' needs exactly one nested <integrator>");
        p.checkUnqueried();
        return loadIntegrator(*p.children()[0], d);
    }
    if (p.type() != "path" && p.type() != "direct")
        failAt(p.location(), "integrator type '", p.type(), "' is not supported (supported: direct, path)");
    d.type = p.type();
    d.maxDepth = p.getInt("max_depth", -1);
    if (d.maxDepth < -1) failAt(p.locationOf("max_depth"), "max_depth must be -1 (unlimited) or >= 0");
    d.rrDepth = p.getInt("rr_depth", 5);
    if (d.rrDepth < 1) failAt(p.locationOf("rr_depth"), "rr_depth must be >= 1");
    d.hideEmitters = p.getBool("hide_emitters", false);
    if (!p.children().empty()) failAt(p.children()[0]->location(), "unexpected <", p.children()[0]->tag(), "> inside <integrator>");
    p.checkUnqueried();
}

void loadFilter(const Properties& p, CameraDescription& cam) {
    if (p.type() == "box") {
        cam.filter = CameraDescription::Filter::Box;
        cam.filterRadius = p.getFloat("radius", 0.5f);
        if (!(cam.filterRadius > 0)) failAt(p.locationOf("radius"), "box filter radius must be positive");
    } else if (p.type() == "gaussian") {
        cam.filter = CameraDescription::Filter::Gaussian;
        cam.gaussianStddev = p.getFloat("stddev", 0.5f);
        if (!(cam.gaussianStddev > 0)) failAt(p.locationOf("stddev"), "gaussian filter stddev must be positive");
        cam.filterRadius = 3.0f * cam.gaussianStddev;  // the film truncates the Gaussian at 3 stddev
    } else if (p.type() == "tent" || p.type() == "mitchell" || p.type() == "catmullrom" || p.type() == "lanczos") {
        failAt(p.location(), "rfilter type '", p.type(), "' is not supported yet (supported: box, gaussian)");
    } else {
        failAt(p.location(), "unknown rfilter type '", p.type(), "' (supported: box, gaussian)");
    }
    p.checkUnqueried();
}

void loadFilm(const Properties& p, CameraDescription& cam) {
    if (p.type() != "hdrfilm") failAt(p.location(), "film type '", p.type(), "' is not supported (supported: hdrfilm)");
    cam.width = p.getInt("width", 768);  // Mitsuba's defaults
    cam.height = p.getInt("height", 576);
    if (cam.width < 1 || cam.height < 1 || cam.width > kMaxFilmSide || cam.height > kMaxFilmSide ||
        int64_t(cam.width) * cam.height > kMaxFilmPixels)
        failAt(p.location(), "film size ", cam.width, "x", cam.height, " is out of range (1..", kMaxFilmSide,
               " per side, at most 2^28 pixels)");
    const std::string fmt = p.getString("pixel_format", "rgb");
    if (fmt != "rgb" && fmt != "rgba")
        failAt(p.locationOf("pixel_format"), "pixel_format '", fmt, "' is not supported (supported: rgb, rgba)");
    const std::string comp = p.getString("component_format", "float32");
    if (comp != "float16" && comp != "float32")
        failAt(p.locationOf("component_format"), "component_format '", comp, "' is not supported (supported: float16, float32)");
    p.getString("file_format", "openexr");  // the output format is chosen by the application
    p.getBool("banner", false);
    PropertiesPtr filter = p.getObject("rfilter", false);
    for (const PropertiesPtr& c : p.children()) {
        if (c->tag() != "rfilter") failAt(c->location(), "unexpected <", c->tag(), "> inside <film>");
        if (filter) failAt(c->location(), "film has more than one rfilter");
        filter = c;
    }
    if (filter) loadFilter(*filter, cam);
    p.checkUnqueried();
}

int loadSampler(const Properties& p) {
    // Every sampler type is accepted: the renderer uses its own sample sequence, only the count matters.
    const int spp = p.getInt("sample_count", 4);
    if (spp < 1 || spp > kMaxSamples) failAt(p.locationOf("sample_count"), "sample_count must be in 1..", kMaxSamples);
    p.getInt("seed", 0);
    p.getInt("dimension", 0);
    p.getBool("jitter", true);
    p.checkUnqueried();
    return spp;
}

void loadSensor(const Properties& p, SceneDescription& scene) {
    if (p.type() != "perspective")
        failAt(p.location(), "sensor type '", p.type(), "' is not supported (supported: perspective)");
    CameraDescription& cam = scene.camera;
    cam.toWorld = p.getTransform("to_world");
    // Default: a 50 mm lens on 36 mm-wide film, fov_x = 2 atan(18 / 50) ≈ 39.6°.
    cam.fovDegrees = p.getFloat("fov", 2.0f * std::atan(18.0f / 50.0f) * 180.0f / kPi);
    if (!(cam.fovDegrees > 0 && cam.fovDegrees < 180)) failAt(p.locationOf("fov"), "fov must be in (0, 180) degrees");
    const std::string axis = p.getString("fov_axis", "x");
    using A = CameraDescription::FovAxis;
    if (axis == "x") cam.fovAxis = A::X;
    else if (axis == "y") cam.fovAxis = A::Y;
    else if (axis == "diagonal") cam.fovAxis = A::Diagonal;
    else if (axis == "smaller") cam.fovAxis = A::Smaller;
    else if (axis == "larger") cam.fovAxis = A::Larger;
    else failAt(p.locationOf("fov_axis"), "fov_axis '", axis, "' is not one of x, y, diagonal, smaller, larger");
    // Accepted and ignored: a pinhole camera has no clipping planes or focus.
    p.getFloat("near_clip", 0.01f);
    p.getFloat("far_clip", 1e4f);
    p.getFloat("focus_distance", 0.0f);
    PropertiesPtr film = p.getObject("film", false), sampler = p.getObject("sampler", false);
    for (const PropertiesPtr& c : p.children()) {
        if (c->tag() != "film" && c->tag() != "sampler")
            failAt(c->location(), "unexpected <", c->tag(), "> inside <sensor> (allowed: film, sampler)");
        PropertiesPtr& slot = c->tag() == "film" ? film : sampler;
        if (slot) failAt(c->location(), "sensor has more than one <", c->tag(), ">");
        slot = c;
    }
    if (film) loadFilm(*film, cam);
    if (sampler) scene.spp = loadSampler(*sampler);
    p.checkUnqueried();
}

void loadEmitter(const Properties& p, SceneDescription& scene) {
    if (p.type() == "area") {
        // Area emitters are attached to shapes; a top-level one only makes sense with an id to <ref>.
        if (p.id().empty()) failAt(p.location(), "an area emitter must be inside a <shape> (or have an id and be referenced from one)");
        return;
    }
    scene.lights.push_back(LightRegistry::instance().create(p));
}

SceneDescription build(ParsedScene parsed) {
    SceneDescription scene;
    scene.sourceFile = parsed.sourceFile;
    bool haveSensor = false, haveIntegrator = false;
    for (const PropertiesPtr& obj : parsed.objects) {
        const Properties& p = *obj;
        const std::string& tag = p.tag();
        if (tag == "shape") {
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
            loadIntegrator(p, scene.integrator);
        } else if (tag == "sampler" || tag == "film" || tag == "rfilter") {
            failAt(p.location(), "<", tag, "> must be inside a <sensor>");
        } else {
            failAt(p.location(), "<", tag, "> is not supported yet");
        }
    }
    return scene;
}

}  // namespace

SceneDescription loadScene(const std::string& path, const std::map<std::string, std::string>& defines) {
    return build(parseSceneFile(path, defines));
}

SceneDescription loadSceneFromString(const std::string& xml, const std::string& baseDir,
                                     const std::map<std::string, std::string>& defines) {
    return build(parseSceneString(xml, baseDir, defines));
}

}  // namespace iris
