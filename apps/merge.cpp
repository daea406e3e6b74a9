// merge: combine renders of one scene into one EXR.
//   merge -o out.exr a.exr b.exr ...            renders with different seeds, weighted by iris.spp
//   merge -o out.exr [--spp N] s0.state s1.state ...   shards of one split render (render --spp-range
//                                                 A:B --checkpoint sI.state): exact, bit-identical to
//                                                 the unsplit render (render/film_shard.h)
// Mismatched sizes, modes, spectral sample counts, scenes, repeated seeds, or shards that do not
// form one complete render are refused (exit 1) with every problem named.
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/io/image.h"
#include "metrics/merge_renders.h"
#include "render/render_output.h"
#include "render/film_shard.h"
#include "spectral/color_management.h"

using namespace iris;

namespace {
const char* kUsage =
    "usage: merge -o out.exr a.exr b.exr ... [--quiet]\n"
    "       merge -o out.exr [--spp N] [--output-space NAME] [--ocio-config FILE] s0.state s1.state ...\n"
    "  EXR inputs: weighted mean of renders of the same scene with different seeds; weights = iris.spp.\n"
    "  Film states (render --spp-range A:B --checkpoint FILE): the exact sum of disjoint sample ranges of\n"
    "  one render, equal bit for bit to the unsplit render; the shards must have the same scene (path and\n"
    "  hash), settings and seed, be complete and cover [0, N) without overlap (--spp N: the expected N).\n"
    "  --check: only check the film states, print their ranges and write nothing.\n";

struct Args {
    std::string out, outputSpace = kColorSpaceLinearRec709, ocioConfig;
    std::vector<std::string> inputs;
    long long spp = -1;
    bool quiet = false, check = false;
};

[[noreturn]] void usageError(const std::string& msg) {
    std::fprintf(stderr, "merge: %s\n%s", msg.c_str(), kUsage);
    std::exit(1);
}

Args parseArgs(int argc, char** argv) {
    Args a;
    for (int i = 1; i < argc; ++i) {
        const std::string s = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc) usageError(s + " needs a value");
            return argv[++i];
        };
        if (s == "-o" || s == "--output") a.out = value();
        else if (s == "--spp") {
            const std::string v = value();
            try {
                size_t pos;
                a.spp = std::stoll(v, &pos);
                if (pos != v.size() || a.spp <= 0) throw std::invalid_argument("");
            } catch (...) {
                usageError("invalid value '" + v + "' for --spp (expected a positive integer)");
            }
        } else if (s == "--output-space") a.outputSpace = value();
        else if (s == "--ocio-config") a.ocioConfig = value();
        else if (s == "--check") a.check = true;
        else if (s == "--quiet" || s == "-q") a.quiet = true;
        else if (s == "-h" || s == "--help") {
            std::printf("%s", kUsage);
            std::exit(0);
        } else if (!s.empty() && s[0] == '-') usageError("unknown option '" + s + "'");
        else a.inputs.push_back(s);
    }
    if ((a.out.empty() && !a.check) || a.inputs.empty()) usageError("need -o out.exr and at least one input");
    for (const std::string& in : a.inputs)
        if (in == a.out) usageError(a.out + ": output would overwrite an input");
    return a;
}

/// Shards of a split render → the EXR the unsplit render writes (same pixels, same conversion).
void mergeFilmStates(const Args& a) {
    std::vector<FilmShard> shards;
    for (const std::string& in : a.inputs) shards.push_back(readFilmShard(in));
    if (a.check)
        for (const FilmShard& s : shards) {
            const std::string why = shardIncompleteness(s);
            std::printf("%s: samples %lld:%lld %s\n", s.path.c_str(), (long long)s.begin, (long long)s.end,
                        why.empty() ? "complete" : why.c_str());
        }
    const MergedFilm m = mergeFilmShards(std::move(shards), a.spp);
    if (a.check) return;
    const bool rgb = settingsField(m.key, "mode") == "rgb";
    const ColorManager colors(a.ocioConfig);
    if (!colors.hasColorSpace(a.outputSpace)) fail("--output-space: colour space '", a.outputSpace, "' is not in ", colors.configPath());
    const ImageMetadata meta = {
        {"iris.version", IRIS_VERSION},
        {"iris.scene", settingsField(m.key, "scene")},
        {"iris.scene_hash", settingsField(m.key, "scene_hash")},
        {"iris.mode", rgb ? "rgb" : "spectral"},
        {"iris.spectral_samples", settingsField(m.key, "n")},
        {"iris.spp", std::to_string(m.spp)},
        {"iris.seed", settingsField(m.key, "seed")},
        {"iris.merged_from", std::to_string(a.inputs.size())},
        {"iris.interrupted", "0"},
        {"iris.integrator", settingsField(m.key, "integrator")},
        {"iris.max_depth", settingsField(m.key, "maxdepth")},
        {"iris.colorspace", a.outputSpace},
        {"iris.ocio_config", colors.configPath()},
    };
    writeEXR(a.out, filmImage(m.film, rgb, colors, a.outputSpace), meta);
    if (!a.quiet)
        std::printf("merged %zu film states -> %s (%dx%d, samples 0:%lld)\n", a.inputs.size(), a.out.c_str(),
                    m.film.width(), m.film.height(), (long long)m.spp);
}

void mergeImages(const Args& a) {
    if (a.check || a.spp >= 0) usageError("--check and --spp apply to film states only");
    const RenderFile merged = mergeRenderFiles(a.inputs);
    writeEXR(a.out, merged.image, merged.meta);
    if (!a.quiet)
        std::printf("merged %zu renders -> %s (%dx%d, spp %s)\n", a.inputs.size(), a.out.c_str(), merged.image.width,
                    merged.image.height, metadataValue(merged.meta, "iris.spp").c_str());
}
}  // namespace

int main(int argc, char** argv) {
    const Args a = parseArgs(argc, argv);
    try {
        size_t states = 0;
        for (const std::string& in : a.inputs) states += isFilmStateFile(in);
        if (states != 0 && states != a.inputs.size()) fail("inputs mix film states and images; merge one kind");
        if (states) mergeFilmStates(a);
        else mergeImages(a);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "merge: %s\n", e.what());
        return 1;
    }
    return 0;
}
