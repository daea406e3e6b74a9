// Sample-count-weighted merge of independent renders. For unbiased per-pixel estimates X_i with
// variance σ²/n_i, the weighted mean Σ n_i X_i / Σ n_i is unbiased with variance σ² / Σ n_i, i.e.
// exactly that of one render with Σ n_i samples (inverse-variance weighting).
#include "metrics/merge_renders.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <set>

#include "core/error.h"

namespace iris {

namespace {

long long parseCount(const RenderFile& f, const std::string& key) {
    const std::string v = metadataValue(f.meta, key);
    if (v.empty()) fail(f.path, ": no '", key, "' in the EXR metadata (was it written by iris render?)");
    char* end = nullptr;
    errno = 0;
    const long long n = std::strtoll(v.c_str(), &end, 10);
    if (errno != 0 || end == v.c_str() || *end != '\0' || n <= 0)
        fail(f.path, ": invalid ", key, " '", v, "' (expected a positive integer)");
    return n;
}

bool parseDouble(const std::string& v, double& out) {
    if (v.empty()) return false;
    char* end = nullptr;
    out = std::strtod(v.c_str(), &end);
    return end != v.c_str() && *end == '\0' && std::isfinite(out);
}

void setMeta(ImageMetadata& meta, const std::string& key, const std::string& value) {
    for (auto& [k, v] : meta)
        if (k == key) {
            v = value;
            return;
        }
    meta.emplace_back(key, value);
}

std::string formatNumber(double x) {
    std::ostringstream os;
    os.precision(17);
    os << x;
    return os.str();
}

}  // namespace

RenderFile mergeRenders(const std::vector<RenderFile>& inputs) {
    if (inputs.empty()) fail("merge: no input images");
    const RenderFile& first = inputs.front();
    std::vector<long long> spp;
    std::set<std::string> seeds;
    std::string seedList;
    for (const RenderFile& f : inputs) {
        spp.push_back(parseCount(f, "iris.spp"));
        if (f.image.width != first.image.width || f.image.height != first.image.height ||
            f.image.channels != first.image.channels || f.image.channelNames != first.image.channelNames)
            fail(f.path, ": size/channels ", f.image.width, "x", f.image.height, "x", f.image.channels,
                 " differ from ", first.path, " (", first.image.width, "x", first.image.height, "x",
                 first.image.channels, ")");
        if (f.image.pixels.size() != f.image.pixelCount() * size_t(f.image.channels))
            fail(f.path, ": pixel buffer does not match the image size");
        for (const char* key : {"iris.mode", "iris.spectral_samples", "iris.scene"}) {
            const std::string a = metadataValue(first.meta, key), b = metadataValue(f.meta, key);
            if (a != b)
                fail(f.path, ": ", key, " '", b, "' differs from '", a, "' in ", first.path,
                     " (only renders of the same scene and settings can be merged)");
        }
        const std::string seed = metadataValue(f.meta, "iris.seed");
        if (!seed.empty()) {
            if (!seeds.insert(seed).second)
                fail(f.path, ": seed ", seed, " appears twice; renders with equal seeds are not independent");
            seedList += (seedList.empty() ? "" : ",") + seed;
        }
    }

    RenderFile out;
    out.path = "merged";
    out.image = first.image;
    long long total = 0;
    for (long long n : spp) total += n;
    // Accumulate in double: Σ n_i x_i / Σ n_i.
    std::vector<double> acc(first.image.pixels.size(), 0.0);
    for (size_t i = 0; i < inputs.size(); ++i) {
        const double w = double(spp[i]);
        const std::vector<float>& px = inputs[i].image.pixels;
        for (size_t j = 0; j < acc.size(); ++j) acc[j] += w * double(px[j]);
    }
    for (size_t j = 0; j < acc.size(); ++j) out.image.pixels[j] = float(acc[j] / double(total));

    out.meta = first.meta;
    setMeta(out.meta, "iris.spp", std::to_string(total));
    setMeta(out.meta, "iris.merged_from", std::to_string(inputs.size()));
    if (!seedList.empty()) setMeta(out.meta, "iris.seed", seedList);
    for (const char* key : {"iris.render_time_s", "iris.rays"}) {
        double sum = 0;
        bool all = true;
        for (const RenderFile& f : inputs) {
            double v = 0;
            if (!parseDouble(metadataValue(f.meta, key), v)) all = false;
            sum += v;
        }
        if (all) setMeta(out.meta, key, formatNumber(sum));
        else {
            for (auto it = out.meta.begin(); it != out.meta.end(); ++it)
                if (it->first == key) {
                    out.meta.erase(it);
                    break;
                }
        }
    }
    return out;
}

RenderFile mergeRenderFiles(const std::vector<std::string>& paths) {
    std::vector<RenderFile> inputs;
    for (const std::string& p : paths) inputs.push_back(RenderFile{p, readImage(p), readEXRMetadata(p)});
    return mergeRenders(inputs);
}

}  // namespace iris
