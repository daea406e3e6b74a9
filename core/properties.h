// Typed, named parameters of one scene object (a Mitsuba-style plugin instance). The scene loader
// fills them from XML; each plugin's factory reads what it knows and calls checkUnqueried(),
// which reports every parameter the plugin did not recognise as "file:line: ..." errors.
#pragma once

#include <map>
#include <memory>
#include <set>
#include <string>
#include <variant>
#include <vector>

#include "core/error.h"
#include "core/mitsuba_convention.h"
#include "core/object_cache.h"
#include "core/math.h"

namespace iris {

class ObjectCache;
class Properties;
using PropertiesPtr = std::shared_ptr<Properties>;

/// A spectrum as written in a scene, converted to a Spectrum only when the plugin says which
/// kind (reflectance, unbounded, illuminant) it needs.
struct SpectrumValue {
    enum class Type { Constant, Pairs, File, Blackbody } type = Type::Constant;
    float constant = 0.0f;
    std::vector<float> lambdas, values;  // Pairs
    std::string path;                    // File (absolute or already resolved)
    float temperature = 6504.0f, scale = 1.0f;  // Blackbody
    /// Whose RGB value a table (Pairs, File) renders with in RGB mode (spectral/mitsuba_rgb.h):
    /// Mitsuba 0.6's in a version 0.x file (set by the upgrade pass), else Mitsuba 3's.
    MitsubaConvention convention = MitsubaConvention::Mitsuba3;
};

struct RGBValue {
    vec3 rgb{0.0f};
};

struct PointValue {
    vec3 v{0.0f};
};
struct VectorValue {
    vec3 v{0.0f};
};

using PropertyValue = std::variant<bool, int64_t, float, std::string, PointValue, VectorValue, RGBValue,
                                   SpectrumValue, mat4, PropertiesPtr>;

class Properties {
public:
    Properties() = default;
    Properties(std::string tag, std::string type, SourceLocation loc)
        : tag_(std::move(tag)), type_(std::move(type)), loc_(std::move(loc)) {}

    const std::string& tag() const { return tag_; }    // "bsdf", "texture", "emitter", ...
    const std::string& type() const { return type_; }  // plugin type, e.g. "diffuse"
    const std::string& id() const { return id_; }
    void setId(std::string id) { id_ = std::move(id); }
    const SourceLocation& location() const { return loc_; }
    /// Major version of the scene format of the file that defines this object (0 = Mitsuba 0.6,
    /// 2 or 3 = Mitsuba 2/3; 3 when built in code). Read only by the upgrade pass
    /// (render/loader/scene_upgrade.h), which turns it into parameters plugins read
    /// (core/mitsuba_convention.h; docs/scene_format.md, "Version-dependent defaults").
    int formatVersion() const { return formatVersion_; }
    void setFormatVersion(int major) { formatVersion_ = major; }
    /// Location of a parameter's own element (falls back to the object's location).
    SourceLocation locationOf(const std::string& name) const;

    /// Set a named parameter; a duplicate name is an error at `loc`.
    void set(const std::string& name, PropertyValue value, const SourceLocation& loc);
    /// For the upgrade pass (render/loader/scene_upgrade.h), before any plugin reads: the stored
    /// value of `name` without marking it as used (nullptr when absent); a new value for `name`,
    /// kept where it was written; `from` renamed to `to` (an error at the later of the two
    /// elements when both are given); the object made another plugin's (Mitsuba 0.6's `principled` is
    /// iris's `disney`).
    const PropertyValue* peek(const std::string& name) const;
    void replace(const std::string& name, PropertyValue value);
    void rename(const std::string& from, const std::string& to);
    void setType(std::string type) { type_ = std::move(type); }
    /// Unnamed nested objects (e.g. the bsdf inside a twosided, shapes' bsdf without a name).
    void addChild(PropertiesPtr child) { children_.push_back(std::move(child)); }
    const std::vector<PropertiesPtr>& children() const { return children_; }
    bool has(const std::string& name) const { return values_.count(name) > 0; }
    std::vector<std::string> names() const;

    // Typed getters: the one-argument forms throw a located error when the parameter is missing;
    // all forms throw when the stored value has the wrong type. Every getter marks the name as used.
    bool getBool(const std::string& name) const;
    bool getBool(const std::string& name, bool def) const;
    int getInt(const std::string& name) const;
    int getInt(const std::string& name, int def) const;
    float getFloat(const std::string& name) const;
    float getFloat(const std::string& name, float def) const;
    std::string getString(const std::string& name) const;
    std::string getString(const std::string& name, const std::string& def) const;
    vec3 getPoint(const std::string& name) const;
    vec3 getPoint(const std::string& name, const vec3& def) const;
    vec3 getVector(const std::string& name) const;
    vec3 getVector(const std::string& name, const vec3& def) const;
    /// An RGB triple given as <rgb> (also accepts a float, replicated).
    vec3 getRGB(const std::string& name, const vec3& def) const;
    mat4 getTransform(const std::string& name, const mat4& def = mat4(1.0f)) const;

    // Spectra and textures are read by free functions of their own layers:
    // getSpectrum (spectral/spectrum_params.h), getSpectrumTexture and getFloatTexture
    // (materials/textures/texture_params.h), through the raw access below.
    /// A nested object given by name (or nullptr when absent and not required).
    PropertiesPtr getObject(const std::string& name, bool required = true) const;

    /// Throw one error with a line "file:line: unknown parameter 'x' of <tag> 'type' (known: ...)"
    /// for every parameter that no getter has read.
    void checkUnqueried() const;

    /// The cache of the load these properties came from (core/object_cache.h), or nullptr for
    /// properties built in code (their objects are then not shared).
    ObjectCache* objectCache() const { return cache_; }
    void setObjectCache(ObjectCache* cache) { cache_ = cache; }

    /// Raw access for the typed getters of higher layers. A stored value and where it was written.
    struct Entry {
        PropertyValue value;
        SourceLocation loc;
    };
    /// The entry of `name` (marked as used), or nullptr when absent.
    const Entry* find(const std::string& name) const;
    /// The nested object stored under `name`, or nullptr when absent or not an object; unlike the
    /// getters it neither marks the name as used nor records it as known (to look before reading).
    const PropertiesPtr* peekObject(const std::string& name) const;
    /// True when `name` is present (recorded as a known parameter, not marked as used).
    bool present(const std::string& name) const;
    /// The entry of `name`, or "file:line: missing required parameter" when absent.
    const Entry& require(const std::string& name) const;
    /// "parameter 'x' of <tag> 'type' must be a <expected>, not a <stored type>".
    [[noreturn]] void typeError(const std::string& name, const char* expected) const;

private:
    ObjectCache* cache_ = nullptr;

    std::string tag_, type_, id_;
    SourceLocation loc_;
    std::map<std::string, Entry> values_;
    std::vector<PropertiesPtr> children_;
    int formatVersion_ = 3;
    mutable std::set<std::string> queried_, asked_;
};

/// The object of type T built from p: the one this load already made from it (a second <ref> to
/// the same id), or make(), kept in the load's cache for the next one (core/object_cache.h).
template <class T, class Make>
std::shared_ptr<T> cachedObject(const Properties& p, Make&& make) {
    ObjectCache* cache = p.objectCache();
    if (cache)
        if (std::shared_ptr<T> hit = cache->find<T>(p)) return hit;
    std::shared_ptr<T> object = make();
    if (cache) cache->store<T>(p, object);
    return object;
}

}  // namespace iris
