// EnvmapNodeBlocks (render/lights/envmap_node_blocks.h): the per-2×2-block node lists of the
// spectral environment map give, bit for bit, the node order and weights of merging the four
// texels' corner nodes one contribution at a time; black texels and the memory cap leave a block
// unstored.
#include <gtest/gtest.h>

#include <bit>
#include <vector>

#include "core/rng.h"
#include "render/lights/envmap_node_blocks.h"

using namespace iris;

namespace {

EnvmapTexelShape shape(float m, std::vector<float> p, std::vector<uint16_t> node) {
    EnvmapTexelShape t;
    t.m = m;
    for (size_t j = 0; j < p.size(); ++j) {
        t.p[j] = p[j];
        t.node[j] = node[j];
        t.pMin = std::min(t.pMin, p[j]);
    }
    return t;
}

/// The merge written out plainly: contributions p_kj · W_k in texel, then corner, order; a node's
/// first contribution starts its weight, later ones add to it.
int referenceMerge(const EnvmapTexelShape* const texel[4], const float w[4], uint16_t* nodes, float* weights) {
    int count = 0;
    for (int k = 0; k < 4; ++k)
        for (int j = 0; j < 4; ++j) {
            if (!(texel[k]->p[j] > 0)) continue;
            const float c = texel[k]->p[j] * w[k];
            int e = 0;
            while (e < count && nodes[e] != texel[k]->node[j]) ++e;
            if (e == count) {
                nodes[count] = texel[k]->node[j];
                weights[count++] = c;
            } else {
                weights[e] += c;
            }
        }
    return count;
}

/// A 3 × 3 map whose texels lie in overlapping cells (shared nodes at different corner positions),
/// one cell with a single corner (a grey-axis texel) and one texel equal to its neighbour's cell.
std::vector<EnvmapTexelShape> mixedTexels() {
    return {shape(1.0f, {0.5f, 0.25f, 0.125f, 0.125f}, {0, 1, 2, 3}), shape(2.0f, {0.6f, 0.4f}, {3, 4}),
            shape(0.5f, {1.0f}, {5}),
            shape(3.0f, {0.1f, 0.2f, 0.3f, 0.4f}, {4, 0, 6, 1}), shape(1.5f, {0.7f, 0.1f, 0.1f, 0.1f}, {0, 1, 2, 3}),
            shape(0.25f, {0.3f, 0.7f}, {7, 2}),
            shape(4.0f, {0.2f, 0.2f, 0.6f}, {8, 9, 0}), shape(0.75f, {0.9f, 0.1f}, {1, 8}), shape(1.25f, {1.0f}, {9})};
}

const EnvmapTexelShape* const* blockTexels(const std::vector<EnvmapTexelShape>& t, int width, int x0, int y0,
                                           const EnvmapTexelShape* out[4]) {
    const int x1 = (x0 + 1) % width;
    out[0] = &t[y0 * width + x0];
    out[1] = &t[y0 * width + x1];
    out[2] = &t[(y0 + 1) * width + x0];
    out[3] = &t[(y0 + 1) * width + x1];
    return out;
}

}  // namespace

TEST(EnvmapNodeBlocks, EveryBlockMatchesTheMergeBitForBit) {
    const std::vector<EnvmapTexelShape> texels = mixedTexels();
    const EnvmapNodeBlocks blocks(texels, 3, 3, size_t(1) << 20);
    Pcg32 rng(7, 1);
    for (int y0 = 0; y0 < 2; ++y0)
        for (int x0 = 0; x0 < 3; ++x0) {  // x0 = 2 wraps to column 0
            const int block = y0 * 3 + x0;
            const EnvmapTexelShape* t[4];
            blockTexels(texels, 3, x0, y0, t);
            ASSERT_GT(blocks.count(block), 0) << block;
            for (int trial = 0; trial < 200; ++trial) {
                const float w[4] = {rng.uniform() + 1e-3f, 7.0f * rng.uniform() + 1e-3f, rng.uniform() + 1e-3f, 0.1f * rng.uniform() + 1e-3f};
                uint16_t refNodes[16];
                float refWeights[16];
                const int count = referenceMerge(t, w, refNodes, refWeights);
                ASSERT_EQ(blocks.count(block), count);
                alignas(16) float weights[16];
                blocks.weights(block, lanes::Float4{w[0], w[1], w[2], w[3]}, weights);
                for (int e = 0; e < count; ++e) {
                    EXPECT_EQ(blocks.nodes(block)[e], refNodes[e]) << block << " " << e;
                    EXPECT_EQ(std::bit_cast<uint32_t>(weights[e]), std::bit_cast<uint32_t>(refWeights[e])) << block << " " << e;
                }
            }
        }
}

TEST(EnvmapNodeBlocks, NodeOrderIsFirstAppearance) {
    const std::vector<EnvmapTexelShape> texels = mixedTexels();
    const EnvmapNodeBlocks blocks(texels, 3, 3, size_t(1) << 20);
    // Block (0, 0): texels 0 {0,1,2,3}, 1 {3,4}, 3 {4,0,6,1}, 4 {0,1,2,3}.
    ASSERT_EQ(blocks.count(0), 6);
    const uint16_t expected[6] = {0, 1, 2, 3, 4, 6};
    for (int e = 0; e < 6; ++e) EXPECT_EQ(blocks.nodes(0)[e], expected[e]);
}

TEST(EnvmapNodeBlocks, ADeliberatelyWrongWeightOrderIsDetected) {
    // The comparison above can fail: the same weights given in another texel order differ.
    const std::vector<EnvmapTexelShape> texels = mixedTexels();
    const EnvmapNodeBlocks blocks(texels, 3, 3, size_t(1) << 20);
    const EnvmapTexelShape* t[4];
    blockTexels(texels, 3, 0, 0, t);
    const float w[4] = {0.3f, 0.9f, 0.7f, 0.2f};
    uint16_t refNodes[16];
    float refWeights[16];
    referenceMerge(t, w, refNodes, refWeights);
    alignas(16) float swapped[16];
    blocks.weights(0, lanes::Float4{w[1], w[0], w[2], w[3]}, swapped);
    EXPECT_NE(std::bit_cast<uint32_t>(swapped[0]), std::bit_cast<uint32_t>(refWeights[0]));
}

TEST(EnvmapNodeBlocks, BlackTexelsAndTheMemoryCapLeaveBlocksUnstored) {
    std::vector<EnvmapTexelShape> texels = mixedTexels();
    texels[4] = EnvmapTexelShape{};  // black: m = 0, no corners
    const EnvmapNodeBlocks blocks(texels, 3, 3, size_t(1) << 20);
    for (int block : {0, 1, 3, 4}) EXPECT_EQ(blocks.count(block), 0) << block;  // the blocks around texel (1, 1)
    EXPECT_GT(blocks.count(2), 0);
    EXPECT_GT(blocks.count(5), 0);

    const EnvmapNodeBlocks full(mixedTexels(), 3, 3, size_t(1) << 20);
    const EnvmapNodeBlocks capped(mixedTexels(), 3, 3, full.bytes() - 1);
    EXPECT_LT(capped.bytes(), full.bytes());
    EXPECT_GT(capped.count(0), 0);  // stored in index order until the cap
    EXPECT_EQ(capped.count(5), 0);
}

TEST(EnvmapNodeBlocks, AOneRowMapHasNoBlocks) {
    const std::vector<EnvmapTexelShape> texels(3, shape(1.0f, {1.0f}, {0}));
    const EnvmapNodeBlocks blocks(texels, 3, 1, size_t(1) << 20);
    EXPECT_EQ(blocks.bytes(), 0u);
}
