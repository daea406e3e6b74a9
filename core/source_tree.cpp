#include "core/source_tree.h"

namespace iris {

const std::string& sourceDir() {
    static const std::string dir = IRIS_SOURCE_DIR;
    return dir;
}

std::string sourcePath(const std::string& relative) { return sourceDir() + "/" + relative; }

}  // namespace iris
