// Merging independent renders of one scene (different seeds) into one estimate, each weighted by
// its sample count: the merged image is what a single render with the summed spp would estimate.
#pragma once

#include <string>
#include <vector>

#include "core/io/image.h"

namespace iris {

/// One render and the string metadata of its EXR header ("iris.spp", "iris.seed", ...).
struct RenderFile {
    std::string path;  // for error messages
    Image image;
    ImageMetadata meta;
};

/// Weighted mean Σ n_i x_i / Σ n_i with n_i = "iris.spp". Output metadata: that of the first input
/// with iris.spp = Σ n_i, iris.render_time_s and iris.rays summed (when all inputs have them),
/// iris.seed = the comma-separated input seeds, iris.merged_from = input count.
/// Throws iris::Error naming the offending file for: fewer than 1 input, a missing/invalid spp,
/// size or channel mismatch, differing iris.mode / iris.spectral_samples / iris.scene, repeated seeds.
RenderFile mergeRenders(const std::vector<RenderFile>& inputs);

/// Read each path (image + EXR metadata) and merge.
RenderFile mergeRenderFiles(const std::vector<std::string>& paths);

}  // namespace iris
