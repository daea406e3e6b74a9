// What a test can see of the shared libraries in its own process (the on-demand modules,
// core/io/plugin_module.h): the path of a mapped library, and a line count for error messages.
#pragma once

#include <algorithm>
#include <fstream>
#include <string>

namespace iris::test {

/// Path of a shared library mapped into this process whose path contains `part` ("" if none).
inline std::string mappedLibrary(const std::string& part) {
    std::ifstream maps("/proc/self/maps");
    for (std::string line; std::getline(maps, line);) {
        const size_t slash = line.find('/');
        if (slash != std::string::npos && line.find(part, slash) != std::string::npos) return line.substr(slash);
    }
    return {};
}

inline int lineCount(const std::string& s) { return int(std::count(s.begin(), s.end(), '\n')); }

}  // namespace iris::test
