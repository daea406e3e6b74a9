// Small scenes for the light-tracing tests (ptracer, bdpt): XML with `$integrator`, `$max_depth`
// and `$res` defaults, rendered in-process, and the files some of them need (an environment map,
// a coarse sphere mesh with smooth vertex normals) written once to the test's temporary folder.
#pragma once

#include <functional>
#include <map>
#include <string>

#include "render/film.h"
#include "render/scene_description.h"

namespace iris::test {

/// A floor, a back wall and a diffuse sphere under `light` (XML of one emitter or emitting shape),
/// seen by `sensor` (XML of a <sensor>, default: a 16×16 perspective view with a box filter).
std::string lightTracingScene(const std::string& light, const std::string& extraShapes = "", const std::string& sensor = "");

/// The perspective sensor of lightTracingScene with another reconstruction filter (XML).
std::string perspectiveSensor(const std::string& rfilter = "<rfilter type=\"box\"/>");

/// The emitters every light type is tested with, by name (point, spot, directional, projector,
/// constant, envmap, area_rectangle, area_sphere, area_textured).
std::map<std::string, std::string> testLights();

/// A folder with env.exr (8×4, a gradient) and icosphere.obj (20 triangles, smooth normals).
const std::string& lightTracingDataDir();

struct RenderSpec {
    std::map<std::string, std::string> defines;
    int spp = 64;
    uint64_t seed = 1;
    bool rgb = false;
    int threads = 2;
    int spectralSamples = 4;
    /// Applied to the loaded scene before rendering (e.g. to replace its integrator).
    std::function<void(SceneDescription&)> edit;
};

/// The scene rendered into a film of its resolution.
Film renderLightTracingScene(const std::string& xml, const RenderSpec& spec);

}  // namespace iris::test
