// Loads the OpenImageIO module (libiris_oiio.so, see core/io/oiio_module.h) with dlopen the first
// time it is needed, so that executables never link OpenImageIO's ~250 shared libraries at
// start-up. Used by core/image.cpp for PNG/JPEG output and for reading non-EXR images.
#pragma once

#include <string>

#include "core/io/oiio_module.h"

namespace iris {

/// The module's entry points.
struct OiioModule {
    std::string path;  // the file that was loaded
    iris_oiio_write_u8_fn writeU8 = nullptr;
    iris_oiio_open_fn open = nullptr;
    iris_oiio_channel_name_fn channelName = nullptr;
    iris_oiio_read_float_fn readFloat = nullptr;
    iris_oiio_close_fn close = nullptr;
};

/// Environment variable naming the module file to load instead of the default location.
constexpr const char* kOiioModuleEnv = "IRIS_OIIO_MODULE";

/// The file the loader tries: $IRIS_OIIO_MODULE if set and non-empty; else libiris_oiio.so in the
/// folder of the running executable (/proc/self/exe), or, if it is not there, in the build folder
/// the library was compiled for.
std::string oiioModulePath();

/// The loaded module (loaded on the first call, thread-safe; a failed load is retried next time).
/// Throws iris::Error "<file>: cannot <action>: the OpenImageIO module <path> could not be loaded
/// (<reason>); ..." naming the image file the caller was working on.
const OiioModule& oiioModule(const std::string& file, const std::string& action);

}  // namespace iris
