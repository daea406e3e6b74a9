// merge: combine renders of one scene made with different seeds into one EXR, weighting each by its
// sample count (EXR metadata "iris.spp"); the output records the summed spp.
//   merge -o out.exr a.exr b.exr ...
// Mismatched sizes, modes, spectral sample counts, scenes or repeated seeds are refused (exit 1).
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/io/image.h"
#include "experiments/metrics/merge_renders.h"

using namespace iris;

namespace {
const char* kUsage =
    "usage: merge -o out.exr a.exr b.exr ... [--quiet]\n"
    "  Weighted mean of renders of the same scene with different seeds; weights = iris.spp.\n";
}

int main(int argc, char** argv) {
    std::string out;
    std::vector<std::string> inputs;
    bool quiet = false;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "-o" || a == "--output") {
            if (i + 1 >= argc) {
                std::fprintf(stderr, "merge: %s needs a file name\n%s", a.c_str(), kUsage);
                return 1;
            }
            out = argv[++i];
        } else if (a == "--quiet" || a == "-q") quiet = true;
        else if (a == "-h" || a == "--help") {
            std::printf("%s", kUsage);
            return 0;
        } else if (!a.empty() && a[0] == '-') {
            std::fprintf(stderr, "merge: unknown option '%s'\n%s", a.c_str(), kUsage);
            return 1;
        } else inputs.push_back(a);
    }
    if (out.empty() || inputs.empty()) {
        std::fprintf(stderr, "merge: need -o out.exr and at least one input\n%s", kUsage);
        return 1;
    }
    for (const std::string& in : inputs)
        if (in == out) {
            std::fprintf(stderr, "merge: %s: output would overwrite an input\n", out.c_str());
            return 1;
        }
    try {
        const RenderFile merged = mergeRenderFiles(inputs);
        writeEXR(out, merged.image, merged.meta);
        if (!quiet)
            std::printf("merged %zu renders -> %s (%dx%d, spp %s)\n", inputs.size(), out.c_str(), merged.image.width,
                        merged.image.height, metadataValue(merged.meta, "iris.spp").c_str());
    } catch (const std::exception& e) {
        std::fprintf(stderr, "merge: %s\n", e.what());
        return 1;
    }
    return 0;
}
