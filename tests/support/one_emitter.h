// The emitter of a one-emitter scene, for the tests of scene-level emitter plugins.
#pragma once

#include <gtest/gtest.h>

#include <string>

#include "render/lights/light.h"
#include "render/loader/scene_loader.h"

namespace iris::test {

/// The only emitter of `<emitter type="type">params</emitter>` in a version 3.0.0 scene.
inline LightPtr loadOneEmitter(const std::string& type, const std::string& params) {
    SceneDescription d = loadSceneFromString("<scene version=\"3.0.0\"><emitter type=\"" + type + "\">" + params + "</emitter></scene>", ".");
    EXPECT_EQ(d.lights.size(), 1u);
    return d.lights.at(0);
}

}  // namespace iris::test
