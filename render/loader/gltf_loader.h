// glTF 2.0 scenes (.gltf, .glb) as iris scenes: docs/gltf.md. The node hierarchy (§3.5) with its
// TRS or matrices, meshes (a mesh several nodes use becomes one shape group with an instance
// per node, unless it emits), perspective cameras (§3.10), KHR_lights_punctual, and the
// materials of render/loader/gltf_material.h.
#pragma once

#include <string>

#include "render/scene_description.h"

namespace iris {

struct GltfOptions {
    std::string camera;         // the camera node or camera name to use; "" = the first one
    std::string envmap;         // an environment map file added as an envmap emitter; "" = none
    int width = 512, height = 0;  // film size; height 0 = from the camera's aspect ratio (else square)
    int spp = 16;
    std::string rgbMode = "point";  // the gltf_pbr thin-film reading in RGB mode
};

/// A whole glTF file as a scene: its camera (or a default one framing the scene from +z), the
/// path integrator, and its lights; without any light or emission, the default environment
/// (a `constant` emitter of radiance 1), unless options.envmap gives one.
SceneDescription loadGltfScene(const std::string& path, const GltfOptions& options = {});

/// loadGltfScene for a file held in memory (`name` in messages, URIs relative to `baseDir`).
SceneDescription loadGltfSceneFromMemory(const std::string& bytes, const std::string& name, const std::string& baseDir,
                                         const GltfOptions& options = {});

/// Add a glTF file's shapes, instances and lights to `scene`, placed by `toWorld` (the XML
/// `<shape type="gltf">`; the file's cameras are ignored there).
void appendGltf(const std::string& path, const mat4& toWorld, const std::string& rgbMode, SceneDescription& scene);

/// True for file names the glTF importer reads (.gltf, .glb, any case).
bool isGltfFile(const std::string& path);

}  // namespace iris
