#include "core/io/oiio_loader.h"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <memory>
#include <mutex>
#include <system_error>

#include "core/error.h"

namespace iris {

namespace {

constexpr const char* kModuleFile = "libiris_oiio.so";

template <typename Fn>
Fn symbol(void* lib, const char* name, std::string& missing) {
    void* p = ::dlsym(lib, name);
    if (!p) missing += missing.empty() ? name : strCat(", ", name);
    return reinterpret_cast<Fn>(p);
}

/// Load and check the module at `path`; returns nullptr and sets `reason` on failure.
std::unique_ptr<OiioModule> load(const std::string& path, std::string& reason) {
    // RTLD_LAZY: function symbols of OpenImageIO's ~250 libraries are bound on first call instead
    // of all at load (7 % fewer instructions for a one-sphere render with PNG, callgrind); the
    // module's own entry points are checked with dlsym below. RTLD_LOCAL: OpenImageIO's symbols
    // stay out of the global namespace. The module is never unloaded (OpenImageIO keeps threads
    // and static state).
    void* lib = ::dlopen(path.c_str(), RTLD_LAZY | RTLD_LOCAL);
    if (!lib) {
        const char* e = ::dlerror();
        reason = e ? e : "dlopen failed";
        return nullptr;
    }
    std::string missing;
    auto version = symbol<iris_oiio_abi_version_fn>(lib, "iris_oiio_abi_version", missing);
    auto m = std::make_unique<OiioModule>();
    m->path = path;
    m->writeU8 = symbol<iris_oiio_write_u8_fn>(lib, "iris_oiio_write_u8", missing);
    m->open = symbol<iris_oiio_open_fn>(lib, "iris_oiio_open", missing);
    m->channelName = symbol<iris_oiio_channel_name_fn>(lib, "iris_oiio_channel_name", missing);
    m->readFloat = symbol<iris_oiio_read_float_fn>(lib, "iris_oiio_read_float", missing);
    m->close = symbol<iris_oiio_close_fn>(lib, "iris_oiio_close", missing);
    if (!missing.empty()) {
        reason = strCat("not an iris OpenImageIO module (missing ", missing, ")");
        return nullptr;  // the library stays mapped; harmless
    }
    if (const int v = version(); v != IRIS_OIIO_ABI_VERSION) {
        reason = strCat("interface version ", v, ", this program needs ", IRIS_OIIO_ABI_VERSION, " (stale build?)");
        return nullptr;
    }
    return m;
}

}  // namespace

std::string oiioModulePath() {
    if (const char* env = std::getenv(kOiioModuleEnv); env && *env) return env;
    std::error_code ec;
    const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (!ec) {
        const std::filesystem::path beside = exe.parent_path() / kModuleFile;
        if (std::filesystem::exists(beside, ec)) return beside.string();
    }
#ifdef IRIS_OIIO_MODULE_DIR
    return (std::filesystem::path(IRIS_OIIO_MODULE_DIR) / kModuleFile).string();
#else
    return ec ? std::string(kModuleFile) : (exe.parent_path() / kModuleFile).string();
#endif
}

const OiioModule& oiioModule(const std::string& file, const std::string& action) {
    static std::mutex mutex;
    static std::unique_ptr<OiioModule> loaded;
    std::lock_guard<std::mutex> lock(mutex);
    if (!loaded) {
        const std::string path = oiioModulePath();
        std::string reason;
        loaded = load(path, reason);
        if (!loaded)
            fail(file, ": cannot ", action, ": the OpenImageIO module ", path, " could not be loaded (", reason,
                 "); it is built beside the executables (target iris_oiio), or set ", kOiioModuleEnv,
                 " to its path");
    }
    return *loaded;
}

}  // namespace iris
