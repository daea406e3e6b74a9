// Where the source tree is: the data the renderer ships (spectral/data, spectral/ocio, scenes/) is
// read from it. Set at configure time for core/source_tree.cpp only, so that no other
// translation unit depends on the checkout's path (which lets ccache share objects between
// checkouts).
#pragma once

#include <string>

namespace iris {

/// Absolute path of the source tree this library was built from (no trailing slash).
const std::string& sourceDir();
/// sourceDir() + "/" + relative.
std::string sourcePath(const std::string& relative);

}  // namespace iris
