// The grid-node merge of a spectral environment-map lookup (envmap_light.cpp), precomputed per 2×2
// texel block. A lookup weighs the grid corners ("nodes") of its four texels: node list and weights
// are the first-appearance order of the texels' nodes (texel k = 0..3, corner j = 0..3, those with
// a positive contribution) and, per node, Σ_k p_kj · W_k added in texel order. When every
// contribution is positive that order depends on the block only, so it is stored with each
// texel's corner weight per node (0 where the texel lacks the node): the weights become four
// products and three sums per four nodes, in the same order (x + 0 = x and 0 + x = x for x ≥ 0,
// so the zero entries change no bit). Blocks with a black texel, and blocks past a memory cap, are
// not stored; the lookup then merges node by node as before.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

#include "spectral/lanes.h"

namespace iris {

/// A texel's chromaticity located in the 17³ grid of envmap_light.cpp: scale m (max component),
/// the trilinear weights p of the cell corners with nonzero weight and their node indices (unused
/// entries p = 0), and pMin, the least used p (1 for a black texel, m = 0).
struct EnvmapTexelShape {
    float m = 0;
    float pMin = 1;
    float p[4] = {0, 0, 0, 0};
    uint16_t node[4] = {0, 0, 0, 0};
    /// The four node indices as one number: equal for texels of the same cell.
    uint64_t cell() const {
        uint64_t c;
        std::memcpy(&c, node, sizeof c);
        return c;
    }
};

class EnvmapNodeBlocks {
public:
    EnvmapNodeBlocks() = default;
    /// Blocks (x0, y0) of a width × height map: texels (x0, y0), (x1, y0), (x0, y0 + 1), (x1, y0 + 1),
    /// x1 = (x0 + 1) mod width, for y0 < height − 1, block index y0 · width + x0; stored in index
    /// order while the table stays within maxBytes.
    EnvmapNodeBlocks(const std::vector<EnvmapTexelShape>& texels, int width, int height, size_t maxBytes);

    /// The block's node count (0: not stored) and node list.
    int count(int block) const { return int(header_[size_t(block)] >> kOffsetBits); }
    const uint16_t* nodes(int block) const { return node_.data() + 4 * size_t(header_[size_t(block)] & kOffsetMask); }
    /// Node weights Σ_k p_kj · W_k (texel order) of a stored block into out[0 … count rounded up to
    /// 4): ((p0·W0 + p1·W1) + p2·W2) + p3·W3, the merge's texel order. Inline: it runs per lookup.
    void weights(int block, lanes::Float4 w, float* out) const {
        const uint32_t h = header_[size_t(block)];
        const Group* g = group_.data() + (h & kOffsetMask);
        const int groups = (int(h >> kOffsetBits) + 3) / 4;
        const lanes::Float4 w0 = lanes::broadcast(w[0]), w1 = lanes::broadcast(w[1]), w2 = lanes::broadcast(w[2]),
                            w3 = lanes::broadcast(w[3]);
        for (int i = 0; i < groups; ++i, ++g) lanes::store(out + 4 * i, ((g->p[0] * w0 + g->p[1] * w1) + g->p[2] * w2) + g->p[3] * w3);
    }

    size_t bytes() const;

private:
    static constexpr int kOffsetBits = 27;  // header: count << 27 | first group
    static constexpr uint32_t kOffsetMask = (1u << kOffsetBits) - 1;
    struct Group {  // four nodes: p[k] = texel k's weights of the four nodes
        lanes::Float4 p[4];
    };
    std::vector<uint32_t> header_;  // per block
    std::vector<Group> group_;
    std::vector<uint16_t> node_;  // four per group
};

}  // namespace iris
