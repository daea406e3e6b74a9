// The ray-tracing geometry of a scene is charged to the memory budget before Embree builds it
// (render/scene_memory.h, issue 38 item 5), held while the Scene lives and refused over the limit.
#include <gtest/gtest.h>

#include "core/memory_budget.h"
#include "render/loader/scene_loader.h"
#include "render/scene.h"
#include "render/scene_memory.h"
#include "tests/support/error_of.h"

using namespace iris;

namespace {

SceneDescription spheres(int n) {
    std::string xml = "<scene version=\"3.0.0\">\n";
    for (int i = 0; i < n; ++i) xml += "<shape type=\"sphere\"><point name=\"center\" x=\"" + std::to_string(3 * i) + "\" y=\"0\" z=\"5\"/></shape>\n";
    return loadSceneFromString(xml + "</scene>\n", ".");
}

}  // namespace

TEST(SceneMemory, GeometryIsChargedBeforeEmbreeBuildsAndHeldWhileTheSceneLives) {
    const uint64_t bytes = sceneGeometryBytes(spheres(1000));
    EXPECT_EQ(bytes, 1000u * (320 + 32));
    const uint64_t before = memoryLimit();
    {
        SceneDescription desc = spheres(1000);
        const uint64_t charged = memoryCharged();
        setMemoryLimit(charged + bytes);  // exactly enough
        const Scene scene(std::move(desc));
        EXPECT_EQ(memoryCharged(), charged + bytes);
        setMemoryLimit(before);
    }
    SceneDescription desc = spheres(1000);
    setMemoryLimit(memoryCharged() + bytes - 1);  // one byte short
    const std::string e = test::errorOf([&] { const Scene scene(std::move(desc)); });
    setMemoryLimit(before);
    EXPECT_NE(e.find("<string>: the ray-tracing geometry of 1000 shapes (0 triangles) and 0 instances needs 344 KiB, over the memory limit"),
              std::string::npos) << e;
}
