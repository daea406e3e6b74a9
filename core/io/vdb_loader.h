// Loads the OpenVDB module (libiris_vdb.so, see core/io/vdb_module.h) with dlopen the first time a
// .vdb grid is read (core/io/vdb_reader.cpp), so that executables never link OpenVDB and its
// libraries at start-up. The search and checks are core/io/plugin_module.h's, as for OpenImageIO.
#pragma once

#include <string>

#include "core/io/vdb_module.h"

namespace iris {

/// The module's entry points.
struct VdbModule {
    std::string path;  // the file that was loaded
    iris_vdb_open_fn open = nullptr;
    iris_vdb_read_dense_fn readDense = nullptr;
    iris_vdb_close_fn close = nullptr;
};

/// Environment variable naming the module file to load instead of the default location.
constexpr const char* kVdbModuleEnv = "IRIS_VDB_MODULE";

/// The file the loader tries: $IRIS_VDB_MODULE if set and non-empty; else libiris_vdb.so in the
/// folder of the running executable (/proc/self/exe), or, if it is not there, in the build folder
/// the library was compiled for.
std::string vdbModulePath();

/// The loaded module (loaded on the first call, thread-safe; a failed load is retried next time).
/// Throws iris::Error "<file>: cannot <action>: the OpenVDB module <path> could not be loaded
/// (<reason>); ..." naming the .vdb file the caller was reading.
const VdbModule& vdbModule(const std::string& file, const std::string& action);

}  // namespace iris
