#include "render/loader/scene_file.h"

#include <cstdlib>

namespace iris {

namespace {

int positive(const std::string& path, const std::string& name, const std::string& value) {
    char* end = nullptr;
    const long v = std::strtol(value.c_str(), &end, 10);
    if (end == value.c_str() || *end || v <= 0 || v > 65536) fail(path, ": -D ", name, "=", value, " must be a whole number in [1, 65536]");
    return int(v);
}

}  // namespace

SceneDescription loadSceneFile(const std::string& path, const std::map<std::string, std::string>& defines, GltfOptions gltf) {
    if (!isGltfFile(path)) return loadScene(path, defines);
    for (const auto& [name, value] : defines) {
        if (name == "res" || name == "width") gltf.width = positive(path, name, value);
        else if (name == "height") gltf.height = positive(path, name, value);
        else if (name == "spp") gltf.spp = positive(path, name, value);
        else if (name == "camera") gltf.camera = value;
        else if (name == "envmap") gltf.envmap = value;
        else if (name == "rgb_mode") gltf.rgbMode = value;
        else fail(path, ": -D ", name, " is not a glTF scene option (res, width, height, spp, camera, envmap, rgb_mode)");
    }
    return loadGltfScene(path, gltf);
}

}  // namespace iris
