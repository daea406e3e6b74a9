#include "render/loader/scene_upgrade.h"

#include <set>
#include <utility>

#include "core/xml/xml_values.h"
#include "render/scene_defaults.h"

namespace iris {

namespace {

// ------------------------------------------------------------------ version rules (0.x → 3)

/// Mitsuba 3, src/core/xml.cpp upgrade_tree (version < 2.0.0): "Upgrade all attribute names from
/// camelCase to underscore_case" (toWorld → to_world, intIOR → int_ior; core/xml/xml_values.h).
void snakeCaseNames(Properties& p) {
    for (const std::string& name : p.names())
        if (const std::string snake = camelToSnake(name); snake != name) p.rename(name, snake);
}

/// Mitsuba 0.6 reads a single-valued <spectrum value="v"/> as the number v (for an emitter
/// v × D65, intent "illuminant"; src/librender/scenehandler.cpp), as a <float> is read in every
/// version; Mitsuba 3 reads it as a flat spectrum (spectral/spectrum_params.h).
void singleValuedSpectraAsNumbers(Properties& p) {
    for (const std::string& name : p.names()) {
        const auto* s = std::get_if<SpectrumValue>(p.peek(name));
        if (s && s->type == SpectrumValue::Type::Constant) p.replace(name, s->constant);
    }
}

/// Mitsuba 0.6, src/bsdfs/conductor.cpp and roughconductor.cpp: the default material is "Cu"
/// (Mitsuba 3: "none", a mirror), and the exterior index `extEta` (default "air", 1.000277)
/// divides η and k; iris's name for it is ext_ior in every version (Mitsuba 3 has none).
void conductorDefaults(Properties& p) {
    if (p.tag() != "bsdf" || (p.type() != "conductor" && p.type() != "roughconductor")) return;
    if (!p.has("eta") && !p.has("k") && !p.has("material")) p.set("material", std::string("Cu"), p.location());
    if (p.has("ext_eta")) {
        if (p.has("ext_ior")) failAt(p.locationOf("ext_ior"), "give either 'ext_eta' (Mitsuba 0.6) or 'ext_ior', not both");
        p.rename("ext_eta", "ext_ior");
    } else if (!p.has("ext_ior")) {
        p.set("ext_ior", 1.000277f, p.location());
    }
}

/// Mitsuba 0.6's normalmap and bumpmap (2014) had neither option of Mitsuba 3's PerturbedBSDF,
/// which turns both on by default (materials/perturbed_frame.h).
void perturbDefaults(Properties& p) {
    if (p.tag() != "bsdf" || (p.type() != "normalmap" && p.type() != "bumpmap")) return;
    for (const char* name : {"flip_invalid_normals", "use_shadowing_function"})
        if (!p.has(name)) p.set(name, false, p.location());
}

/// The plugins with a model of each Mitsuba (docs/scene_format.md, "Version-dependent defaults"):
/// each reads `convention` (core/mitsuba_convention.h) in every form of its parameters.
bool hasTwoModels(const Properties& p) {
    static const std::set<std::pair<std::string, std::string>> kTwoModels = {
        {"bsdf", "roughplastic"}, {"bsdf", "blendbsdf"}, {"bsdf", "mask"},          {"bsdf", "conductor"},
        {"bsdf", "roughconductor"}, {"texture", "checkerboard"}, {"emitter", "envmap"},
        {"spectrum", "regular"},  {"spectrum", "irregular"}};
    return kTwoModels.count({p.tag(), p.type()}) > 0;
}

/// Mitsuba 0.6's model where the two Mitsubas differ: `convention` "mitsuba0.6" on the plugins that
/// have both (unless the scene gives one), and on every tabulated spectrum value (the RGB value
/// Mitsuba 0.6's RGB build renders it with, spectral/mitsuba_rgb.h).
void mitsuba06Models(Properties& p) {
    if (hasTwoModels(p) && !p.has("convention"))
        p.set("convention", std::string(conventionName(MitsubaConvention::Mitsuba06)), p.location());
    for (const std::string& name : p.names()) {
        const auto* s = std::get_if<SpectrumValue>(p.peek(name));
        if (!s || (s->type != SpectrumValue::Type::Pairs && s->type != SpectrumValue::Type::File)) continue;
        SpectrumValue table = *s;
        table.convention = MitsubaConvention::Mitsuba06;
        p.replace(name, std::move(table));
    }
}

/// Mitsuba 0.6 has no principled plugin: a 0.x scene's `principled` is iris's Disney 2012 BRDF,
/// `disney`, which `principled` meant before Mitsuba 3's model was added (materials/principled.h).
void principledIsDisney(Properties& p) {
    if (p.tag() == "bsdf" && p.type() == "principled") p.setType("disney");
}

void upgradeFromVersion0(Properties& p) {
    snakeCaseNames(p);
    singleValuedSpectraAsNumbers(p);
    conductorDefaults(p);
    perturbDefaults(p);
    mitsuba06Models(p);
    principledIsDisney(p);
}

/// Every object once, nested ones and <ref>erenced ones included.
void upgradeObjectOnce(Properties& p, std::set<const Properties*>& done) {
    if (!done.insert(&p).second) return;
    if (p.formatVersion() < 2) upgradeFromVersion0(p);
    for (const std::string& name : p.names())
        if (const auto* obj = std::get_if<PropertiesPtr>(p.peek(name))) upgradeObjectOnce(**obj, done);
    for (const PropertiesPtr& child : p.children()) upgradeObjectOnce(*child, done);
}

// ------------------------------------------------------------------ defaults (render/scene_defaults.h)

PropertiesPtr defaultObject(const ParsedScene& scene, const char* tag, const char* type, const SourceLocation& at) {
    auto p = std::make_shared<Properties>(tag, type, at);
    p->setObjectCache(scene.cache.get());
    return p;
}

/// The object `p` has under `tag`, named `tag` or nested without a name (the loader refuses two).
bool hasObject(const Properties& p, const std::string& tag) {
    if (p.peekObject(tag)) return true;
    for (const PropertiesPtr& c : p.children())
        if (c->tag() == tag) return true;
    return false;
}

PropertiesPtr namedOrNested(const Properties& p, const std::string& tag) {
    if (const PropertiesPtr* named = p.peekObject(tag)) return *named;
    for (const PropertiesPtr& c : p.children())
        if (c->tag() == tag) return c;
    return nullptr;
}

void fillSensor(const ParsedScene& scene, Properties& sensor) {
    if (!hasObject(sensor, "film")) sensor.addChild(defaultObject(scene, "film", kDefaultFilm, sensor.location()));
    if (!hasObject(sensor, "sampler")) {
        PropertiesPtr sampler = defaultObject(scene, "sampler", kDefaultSampler, sensor.location());
        sampler->set("sample_count", int64_t(kDefaultSampleCount), sensor.location());
        sensor.addChild(std::move(sampler));
    }
    const PropertiesPtr film = namedOrNested(sensor, "film");
    if (film->tag() == "film" && !hasObject(*film, "rfilter"))
        film->addChild(defaultObject(scene, "rfilter", kDefaultFilter, film->location()));
}

void fillDefaults(ParsedScene& scene) {
    bool sensor = false, integrator = false;
    for (const PropertiesPtr& obj : scene.objects) {
        if (obj->tag() == "sensor") {
            sensor = true;
            fillSensor(scene, *obj);
        }
        integrator |= obj->tag() == "integrator";
    }
    if (!sensor) {  // Mitsuba's default sensor
        PropertiesPtr s = defaultObject(scene, "sensor", kDefaultSensor, {scene.sourceFile, 0});
        fillSensor(scene, *s);
        scene.objects.push_back(std::move(s));
    }
    if (!integrator) scene.objects.push_back(defaultObject(scene, "integrator", kDefaultIntegrator, {}));
}

}  // namespace

void upgradeObject(Properties& p) {
    std::set<const Properties*> done;
    upgradeObjectOnce(p, done);
}

void upgradeScene(ParsedScene& scene) {
    std::set<const Properties*> done;
    for (const PropertiesPtr& obj : scene.objects) upgradeObjectOnce(*obj, done);
    fillDefaults(scene);
}

}  // namespace iris
