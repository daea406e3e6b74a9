// One entry point for every scene file the programs open: Mitsuba XML (scene_loader.h) or glTF
// 2.0 (gltf_loader.h), told apart by the file name's extension (.gltf, .glb).
#pragma once

#include <map>
#include <string>

#include "render/loader/gltf_loader.h"
#include "render/loader/scene_loader.h"

namespace iris {

/// Load `path`. For XML files `defines` override <default> values; for glTF files they may set
/// `res` (film width), `width`, `height`, `spp`, `camera`, `envmap` and `rgb_mode`, which override
/// `gltf` (any other name is an error naming it).
SceneDescription loadSceneFile(const std::string& path, const std::map<std::string, std::string>& defines = {},
                               GltfOptions gltf = {});

}  // namespace iris
