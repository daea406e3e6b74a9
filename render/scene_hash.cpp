#include "render/scene_hash.h"

#include <cstdint>
#include <cstdio>

#include "core/error.h"
#include "core/input_file.h"

namespace iris {

namespace {
// FNV-1a, 64 bit (Fowler, Noll, Vo; offset basis and prime of the reference description).
void fnv1a(uint64_t& h, const std::string& bytes) {
    for (unsigned char b : bytes) {
        h ^= b;
        h *= 0x100000001b3ull;
    }
}
}  // namespace

std::string sceneHash(const std::string& scenePath, const std::map<std::string, std::string>& defines) {
    const std::string text = readInputFile(scenePath, "scene file", kMaxSceneFileBytes);
    uint64_t h = 0xcbf29ce484222325ull;
    fnv1a(h, text);
    for (const auto& [name, value] : defines) fnv1a(h, std::string(1, '\0') + name + "=" + value);  // sorted by name
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx", (unsigned long long)h);
    return hex;
}

}  // namespace iris
