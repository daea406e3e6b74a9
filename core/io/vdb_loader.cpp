#include "core/io/vdb_loader.h"

#include "core/io/plugin_module.h"

namespace iris {

namespace {

constexpr PluginModuleName kModule{"libiris_vdb.so", kVdbModuleEnv, "OpenVDB", "iris_vdb"};

/// Load and check the module at `path`; returns nullptr and sets `reason` on failure. The module
/// is never unloaded (OpenVDB keeps registries and static state once initialised).
std::unique_ptr<VdbModule> load(const std::string& path, std::string& reason) {
    PluginModule lib;
    if (!lib.open(path, reason)) return nullptr;
    auto version = lib.symbol<iris_vdb_abi_version_fn>("iris_vdb_abi_version");
    auto m = std::make_unique<VdbModule>();
    m->path = path;
    m->open = lib.symbol<iris_vdb_open_fn>("iris_vdb_open");
    m->readDense = lib.symbol<iris_vdb_read_dense_fn>("iris_vdb_read_dense");
    m->close = lib.symbol<iris_vdb_close_fn>("iris_vdb_close");
    if (!lib.check(version, IRIS_VDB_ABI_VERSION, kModule.kind, reason)) return nullptr;
    return m;
}

}  // namespace

std::string vdbModulePath() { return pluginModulePath(kModule.file, kModule.envVar); }

const VdbModule& vdbModule(const std::string& file, const std::string& action) {
    return loadedModule(kModule, load, file, action);
}

}  // namespace iris
