#include "core/io/oiio_loader.h"

#include <memory>
#include <mutex>

#include "core/io/plugin_module.h"

namespace iris {

namespace {

constexpr const char* kModuleFile = "libiris_oiio.so";

/// Load and check the module at `path`; returns nullptr and sets `reason` on failure. The module
/// is never unloaded (OpenImageIO keeps threads and static state).
std::unique_ptr<OiioModule> load(const std::string& path, std::string& reason) {
    PluginModule lib;
    if (!lib.open(path, reason)) return nullptr;
    auto version = lib.symbol<iris_oiio_abi_version_fn>("iris_oiio_abi_version");
    auto m = std::make_unique<OiioModule>();
    m->path = path;
    m->writeU8 = lib.symbol<iris_oiio_write_u8_fn>("iris_oiio_write_u8");
    m->open = lib.symbol<iris_oiio_open_fn>("iris_oiio_open");
    m->channelName = lib.symbol<iris_oiio_channel_name_fn>("iris_oiio_channel_name");
    m->readFloat = lib.symbol<iris_oiio_read_float_fn>("iris_oiio_read_float");
    m->close = lib.symbol<iris_oiio_close_fn>("iris_oiio_close");
    if (!lib.check(version, IRIS_OIIO_ABI_VERSION, "OpenImageIO", reason)) return nullptr;
    return m;
}

}  // namespace

std::string oiioModulePath() { return pluginModulePath(kModuleFile, kOiioModuleEnv); }

const OiioModule& oiioModule(const std::string& file, const std::string& action) {
    static std::mutex mutex;
    static std::unique_ptr<OiioModule> loaded;
    std::lock_guard<std::mutex> lock(mutex);
    if (!loaded) {
        const std::string path = oiioModulePath();
        std::string reason;
        loaded = load(path, reason);
        if (!loaded) failModuleLoad(file, action, "OpenImageIO", path, reason, "iris_oiio", kOiioModuleEnv);
    }
    return *loaded;
}

}  // namespace iris
