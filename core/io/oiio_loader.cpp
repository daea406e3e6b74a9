#include "core/io/oiio_loader.h"

#include "core/io/plugin_module.h"

namespace iris {

namespace {

constexpr PluginModuleName kModule{"libiris_oiio.so", kOiioModuleEnv, "OpenImageIO", "iris_oiio"};

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
    if (!lib.check(version, IRIS_OIIO_ABI_VERSION, kModule.kind, reason)) return nullptr;
    return m;
}

}  // namespace

std::string oiioModulePath() { return pluginModulePath(kModule.file, kModule.envVar); }

const OiioModule& oiioModule(const std::string& file, const std::string& action) {
    return loadedModule(kModule, load, file, action);
}

}  // namespace iris
