// Plugins registered by name (as in Mitsuba): every object kind a scene file can name (shapes,
// sensors, films, reconstruction filters, samplers, integrators, emitters, textures, BSDFs,
// spectra) registers a factory under its scene-file name; the scene loader creates objects
// through these registries, so adding a plugin touches only the plugin's own file. Registration
// happens in static initialisers, so the library is linked as a whole archive (see CMakeLists.txt);
// a name registered twice in one registry stops the program at start-up.
#pragma once

#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/properties.h"

namespace iris {

template <typename T, typename... Extra>
class Registry {
public:
    using Factory = std::function<std::shared_ptr<T>(const Properties&, Extra...)>;

    static Registry& instance() {
        static Registry r;
        return r;
    }
    /// Register a factory; a name already present is an error (two plugins cannot share a name).
    void add(const std::string& name, Factory f) {
        if (!factories_.emplace(name, std::move(f)).second)
            fail("plugin name '", name, "' is registered twice in one registry");
    }
    bool has(const std::string& name) const { return factories_.count(name) > 0; }
    std::vector<std::string> names() const {
        std::vector<std::string> n;
        for (const auto& [k, v] : factories_) n.push_back(k);
        return n;
    }
    /// Create an object; unknown types give "file:line: unknown <tag> type 'x' (supported: ...)".
    std::shared_ptr<T> create(const Properties& props, Extra... extra) const {
        const auto it = factories_.find(props.type());
        if (it == factories_.end()) failUnknownType(props);
        auto obj = it->second(props, extra...);
        props.checkUnqueried();
        return obj;
    }

    /// Advice for a known plugin of the scene format that iris cannot honour ("use ... instead"),
    /// added to its "unknown type" message.
    void addHint(const std::string& name, const std::string& advice) { hints_[name] = advice; }

    /// The one message for a type no plugin registered:
    /// "file:line: unknown <tag> type 'x' (supported: a, b, ...)[: advice]".
    /// A type that differs from a plugin's name only in case (`Rectangle`) is named: Mitsuba loads
    /// plugins from files named after the type (src/core/plugin.cpp), so such scenes load only
    /// where the file system ignores case, and iris, like Mitsuba on Linux, refuses them.
    [[noreturn]] void failUnknownType(const Properties& props) const {
        std::string list;
        for (const auto& n : names()) list += (list.empty() ? "" : ", ") + n;
        const auto hint = hints_.find(props.type());
        std::string lower = props.type();
        for (char& c : lower) c = char(std::tolower(static_cast<unsigned char>(c)));
        const std::string caseHint = lower != props.type() && has(lower)
            ? ": plugin names are lower case, write '" + lower + "' (Mitsuba finds '" + props.type() +
                  "' only on a file system that ignores case)"
            : std::string();
        failAt(props.location(), "unknown ", props.tag(), " type '", props.type(), "' (supported: ", list, ")",
               hint == hints_.end() ? caseHint : ": " + hint->second);
    }

private:
    std::map<std::string, Factory> factories_;
    std::map<std::string, std::string> hints_;
};

// Each object kind declares its registry beside its interface, in its own layer (for example
// MaterialRegistry in materials/material.h): this header names no type above core/.

/// Static registration helper: `static Registrar<MaterialRegistry> reg("diffuse", &create);`
/// A duplicate name is reported on stderr and the program exits with status 1 (exceptions cannot
/// leave a static initialiser).
template <typename R>
struct Registrar {
    Registrar(const std::string& name, typename R::Factory f) {
        try {
            R::instance().add(name, std::move(f));
        } catch (const Error& e) {
            std::fprintf(stderr, "iris: start-up error: %s\n", e.what());
            std::exit(1);
        }
    }
};

/// Static registration of advice: `static HintRegistrar<MaterialRegistry> h("null", "use ...");`
template <typename R>
struct HintRegistrar {
    HintRegistrar(const std::string& name, const std::string& advice) { R::instance().addHint(name, advice); }
};

#define IRIS_CONCAT_IMPL(a, b) a##b
#define IRIS_CONCAT(a, b) IRIS_CONCAT_IMPL(a, b)
/// IRIS_REGISTER(MaterialRegistry, "diffuse", factoryFunction);
#define IRIS_REGISTER(REGISTRY, NAME, FACTORY) \
    static ::iris::Registrar<::iris::REGISTRY> IRIS_CONCAT(irisRegistrar_, __LINE__)(NAME, FACTORY)
/// IRIS_HINT(MaterialRegistry, "null", "what to use instead");
#define IRIS_HINT(REGISTRY, NAME, ADVICE) \
    static ::iris::HintRegistrar<::iris::REGISTRY> IRIS_CONCAT(irisHint_, __LINE__)(NAME, ADVICE)

}  // namespace iris
