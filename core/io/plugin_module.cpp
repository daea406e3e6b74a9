#include "core/io/plugin_module.h"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <system_error>

#include "core/error.h"

namespace iris {

std::string pluginModulePath(const char* fileName, const char* envVar) {
    if (const char* env = std::getenv(envVar); env && *env) return env;
    std::error_code ec;
    const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (!ec) {
        const std::filesystem::path beside = exe.parent_path() / fileName;
        if (std::filesystem::exists(beside, ec)) return beside.string();
    }
#ifdef IRIS_PLUGIN_MODULE_DIR
    return (std::filesystem::path(IRIS_PLUGIN_MODULE_DIR) / fileName).string();
#else
    return ec ? std::string(fileName) : (exe.parent_path() / fileName).string();
#endif
}

bool PluginModule::open(const std::string& path, std::string& reason) {
    // RTLD_LAZY: the function symbols of the libraries behind a module (OpenImageIO's ~250) are
    // bound on first call instead of all at load (7 % fewer instructions for a one-sphere render
    // with PNG, callgrind); the module's own entry points are checked with dlsym. RTLD_LOCAL: those
    // libraries' symbols stay out of the global namespace.
    lib_ = ::dlopen(path.c_str(), RTLD_LAZY | RTLD_LOCAL);
    if (lib_) return true;
    const char* e = ::dlerror();
    reason = e ? e : "dlopen failed";
    return false;
}

void* PluginModule::lookup(const char* name) {
    void* p = lib_ ? ::dlsym(lib_, name) : nullptr;
    if (!p) missing_ += missing_.empty() ? name : strCat(", ", name);
    return p;
}

bool PluginModule::check(int (*version)(), int expected, const std::string& kind, std::string& reason) const {
    if (!missing_.empty()) {
        reason = strCat("not an iris ", kind, " module (missing ", missing_, ")");
        return false;  // the library stays mapped; harmless
    }
    if (const int v = version(); v != expected) {
        reason = strCat("interface version ", v, ", this program needs ", expected, " (stale build?)");
        return false;
    }
    return true;
}

void failModuleLoad(const std::string& file, const std::string& action, const std::string& kind,
                    const std::string& path, const std::string& reason, const char* target, const char* envVar) {
    fail(file, ": cannot ", action, ": the ", kind, " module ", path, " could not be loaded (", reason,
         "); it is built beside the executables (target ", target, "), or set ", envVar, " to its path");
}

}  // namespace iris
