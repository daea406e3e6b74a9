// openEdgeCount (core/mesh.h): the closed-surface test a participating medium's boundary must pass.
#include <gtest/gtest.h>

#include "core/mesh.h"

using namespace iris;

TEST(MeshTopology, ClosedAndOpenSurfaces) {
    EXPECT_EQ(openEdgeCount(makeCube()), 0u);
    EXPECT_EQ(openEdgeCount(makeRectangle()), 4u);  // a square: its four border edges
    EXPECT_GT(openEdgeCount(makeDisk(16)), 0u);
    // Vertices split per face (as at uv seams) are welded by position: still closed.
    TriangleMesh split = makeCube();
    TriangleMesh unshared;
    for (uint32_t i : split.indices) {
        unshared.indices.push_back(uint32_t(unshared.positions.size()));
        unshared.positions.push_back(split.positions[i]);
    }
    EXPECT_EQ(openEdgeCount(unshared), 0u);
    // One triangle removed opens the three edges it shared.
    unshared.indices.resize(unshared.indices.size() - 3);
    EXPECT_EQ(openEdgeCount(unshared), 3u);
}
