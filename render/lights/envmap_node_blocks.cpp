#include "render/lights/envmap_node_blocks.h"

namespace iris {

namespace {
/// The nodes of four texels in first-appearance order (texel, then corner; corners with p > 0).
int firstAppearance(const EnvmapTexelShape* const texel[4], uint16_t* nodes) {
    int count = 0;
    for (int k = 0; k < 4; ++k)
        for (int j = 0; j < 4; ++j) {
            if (!(texel[k]->p[j] > 0)) continue;
            int e = 0;
            while (e < count && nodes[e] != texel[k]->node[j]) ++e;
            if (e == count) nodes[count++] = texel[k]->node[j];
        }
    return count;
}

/// Texel t's corner weight of node n, 0 if its cell lacks n.
float weightOfNode(const EnvmapTexelShape& t, uint16_t n) {
    for (int j = 0; j < 4; ++j)
        if (t.p[j] > 0 && t.node[j] == n) return t.p[j];
    return 0.0f;
}
}  // namespace

EnvmapNodeBlocks::EnvmapNodeBlocks(const std::vector<EnvmapTexelShape>& texels, int width, int height, size_t maxBytes) {
    const int rows = height > 1 ? height - 1 : 0;
    header_.assign(size_t(width) * rows, 0);
    for (int y0 = 0; y0 < rows; ++y0)
        for (int x0 = 0; x0 < width; ++x0) {
            const int x1 = x0 + 1 == width ? 0 : x0 + 1;
            const EnvmapTexelShape* const texel[4] = {&texels[size_t(y0) * width + x0], &texels[size_t(y0) * width + x1],
                                                      &texels[size_t(y0 + 1) * width + x0], &texels[size_t(y0 + 1) * width + x1]};
            bool black = false;
            for (const EnvmapTexelShape* t : texel) black = black || !(t->m > 0);
            if (black) continue;
            uint16_t nodes[16];
            const int count = firstAppearance(texel, nodes);
            const int groups = (count + 3) / 4;
            if (group_.size() + groups > kOffsetMask || bytes() + groups * (sizeof(Group) + 4 * sizeof(uint16_t)) > maxBytes) return;
            header_[size_t(y0) * width + x0] = uint32_t(count) << kOffsetBits | uint32_t(group_.size());
            for (int g = 0; g < groups; ++g) {
                Group group;
                for (int s = 0; s < 4; ++s) {
                    const int e = 4 * g + s;
                    node_.push_back(e < count ? nodes[e] : 0);
                    for (int k = 0; k < 4; ++k) group.p[k][s] = e < count ? weightOfNode(*texel[k], nodes[e]) : 0.0f;
                }
                group_.push_back(group);
            }
        }
}

size_t EnvmapNodeBlocks::bytes() const {
    return header_.size() * sizeof(uint32_t) + group_.size() * sizeof(Group) + node_.size() * sizeof(uint16_t);
}

}  // namespace iris
