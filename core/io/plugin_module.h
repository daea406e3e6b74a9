// What the loaders of iris's on-demand modules share (core/io/oiio_loader.cpp for libiris_oiio.so,
// core/io/vdb_loader.cpp for libiris_vdb.so): where the module file is, opening it with dlopen,
// looking up its C entry points and checking its interface version, and the one-line error when it
// cannot be used. The modules exist so that the executables do not link heavy libraries
// (OpenImageIO, OpenVDB) whose relocation would cost every process its start-up time.
#pragma once

#include <memory>
#include <mutex>
#include <string>

namespace iris {

/// The module file to load: $envVar if set and non-empty; else fileName in the folder of the
/// running executable (/proc/self/exe) if it is there; else in the build folder the library was
/// compiled for (IRIS_PLUGIN_MODULE_DIR), where CMake puts the modules (a Python interpreter or a
/// test binary elsewhere then still finds them).
std::string pluginModulePath(const char* fileName, const char* envVar);

/// A module opened with dlopen. It is never closed: the libraries behind it keep threads and static
/// state, and the loaders keep it for the life of the process.
class PluginModule {
public:
    /// dlopen `path`; false with `reason` (the loader's message) on failure.
    bool open(const std::string& path, std::string& reason);

    /// The entry point `name`, or nullptr; a missing name is remembered for check().
    template <typename Fn>
    Fn symbol(const char* name) {
        return reinterpret_cast<Fn>(lookup(name));
    }

    /// After the lookups: true if every symbol was found and version() returns `expected`; else
    /// false with `reason`: "not an iris <kind> module (missing a, b)" (version() is not called
    /// then), or "interface version v, this program needs n (stale build?)".
    bool check(int (*version)(), int expected, const std::string& kind, std::string& reason) const;

private:
    void* lookup(const char* name);

    void* lib_ = nullptr;
    std::string missing_;  // names not found, comma-separated
};

/// Throws iris::Error "<file>: cannot <action>: the <kind> module <path> could not be loaded
/// (<reason>); it is built beside the executables (target <target>), or set <envVar> to its path".
[[noreturn]] void failModuleLoad(const std::string& file, const std::string& action, const std::string& kind,
                                 const std::string& path, const std::string& reason, const char* target, const char* envVar);

/// One module as its loader names it: the file, the environment variable that overrides its path,
/// the library it wraps (for messages) and its CMake target.
struct PluginModuleName {
    const char* file;
    const char* envVar;
    const char* kind;
    const char* target;
};

/// The module that `load(path, reason)` makes of the file pluginModulePath finds, loaded on the
/// first call (thread-safe; a failed load is retried next time; one per Module type); otherwise
/// failModuleLoad naming `file` (what the caller was working on) and `action`.
template <typename Module>
const Module& loadedModule(const PluginModuleName& name, std::unique_ptr<Module> (*load)(const std::string&, std::string&),
                           const std::string& file, const std::string& action) {
    static std::mutex mutex;
    static std::unique_ptr<Module> loaded;
    std::lock_guard<std::mutex> lock(mutex);
    if (!loaded) {
        const std::string path = pluginModulePath(name.file, name.envVar);
        std::string reason;
        loaded = load(path, reason);
        if (!loaded) failModuleLoad(file, action, name.kind, path, reason, name.target, name.envVar);
    }
    return *loaded;
}

}  // namespace iris
