// Scene loading: a Mitsuba XML scene (0.6 or 3 syntax, see docs/scene_format.md) → SceneDescription.
// Materials, textures and lights are created through their registries (core/registry.h).
#pragma once

#include <map>
#include <string>

#include "render/scene_description.h"

namespace iris {

/// Load a scene file. `defines` override its <default> parameters (the -D name=value option).
/// Throws iris::Error "file:line: message" for every problem.
SceneDescription loadScene(const std::string& path, const std::map<std::string, std::string>& defines = {});

/// Load scene XML held in memory; relative paths resolve against `baseDir`; messages name "<string>".
SceneDescription loadSceneFromString(const std::string& xml, const std::string& baseDir,
                                     const std::map<std::string, std::string>& defines = {});

}  // namespace iris
