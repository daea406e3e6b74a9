// compare: error metrics of a test image against a reference (like OpenImageIO's idiff).
//   compare test.exr ref.exr [--json] [--diff out.exr|out.png]
// Prints MSE, relMSE, PSNR, mean / p99 / max CIEDE2000 (definitions in docs/metrics.md); exit 0.
// Errors (unreadable file, size mismatch, bad arguments) print one line and exit 1.
#include <cctype>
#include <cmath>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/io/image.h"
#include "experiments/metrics/image_metrics.h"

using namespace iris;

namespace {

const char* kUsage =
    "usage: compare test.exr ref.exr [--json] [--diff out.exr|out.png]\n"
    "  --json        print the metrics as one JSON object\n"
    "  --diff FILE   write test-ref (R,G,B) and the per-pixel CIEDE2000 (channel dE00) to an EXR,\n"
    "                or the CIEDE2000 map scaled by 1/10 (white = 10) to an 8-bit PNG/JPEG\n";

std::string jsonString(const std::string& s) {
    std::string out = "\"";
    for (char ch : s) {
        const unsigned char c = static_cast<unsigned char>(ch);
        if (c == '"' || c == '\\') out += std::string("\\") + ch;
        else if (c < 0x20) {
            char buf[8];
            std::snprintf(buf, sizeof buf, "\\u%04x", c);
            out += buf;
        } else out += ch;
    }
    return out + "\"";
}

/// JSON number; non-finite values (PSNR of identical images) become null.
std::string jsonNumber(double v) {
    if (!std::isfinite(v)) return "null";
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.9g", v);
    return buf;
}

bool endsWith(const std::string& s, const std::string& suffix) {
    if (s.size() < suffix.size()) return false;
    std::string tail = s.substr(s.size() - suffix.size());
    for (char& c : tail) c = char(std::tolower(static_cast<unsigned char>(c)));
    return tail == suffix;
}

void writeDiff(const std::string& path, const Image& test, const Image& ref) {
    const Image diff = differenceImage(test, ref);
    const Image de = deltaE00Map(test, ref);
    if (endsWith(path, ".exr")) {
        Image out(diff.width, diff.height, diff.channels + 1);
        out.channelNames = diff.channels == 3 ? std::vector<std::string>{"R", "G", "B", "dE00"}
                                              : std::vector<std::string>{"Y", "dE00"};
        for (size_t p = 0; p < diff.pixelCount(); ++p) {
            for (int c = 0; c < diff.channels; ++c)
                out.pixels[p * size_t(out.channels) + size_t(c)] = diff.pixels[p * size_t(diff.channels) + size_t(c)];
            out.pixels[p * size_t(out.channels) + size_t(diff.channels)] = de.pixels[p];
        }
        writeEXR(path, out, {{"iris.compare.test", "test-ref"}});
    } else {
        Image out(de.width, de.height, 3);
        for (size_t p = 0; p < de.pixelCount(); ++p)
            for (int c = 0; c < 3; ++c) out.pixels[3 * p + size_t(c)] = std::isfinite(de.pixels[p]) ? de.pixels[p] / 10.0f : 1.0f;
        writeLDR(path, out);
    }
}

}  // namespace

int main(int argc, char** argv) {
    std::vector<std::string> files;
    bool json = false;
    std::string diffPath;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--json") json = true;
        else if (a == "--diff") {
            if (i + 1 >= argc) {
                std::fprintf(stderr, "compare: --diff needs a file name\n%s", kUsage);
                return 1;
            }
            diffPath = argv[++i];
        } else if (a == "-h" || a == "--help") {
            std::printf("%s", kUsage);
            return 0;
        } else if (!a.empty() && a[0] == '-') {
            std::fprintf(stderr, "compare: unknown option '%s'\n%s", a.c_str(), kUsage);
            return 1;
        } else files.push_back(a);
    }
    if (files.size() != 2) {
        std::fprintf(stderr, "compare: expected 2 images (test and reference), got %zu\n%s", files.size(), kUsage);
        return 1;
    }
    try {
        const Image test = readImage(files[0]);
        const Image ref = readImage(files[1]);
        ImageErrors e;
        try {
            e = compareImages(test, ref);
        } catch (const Error& err) {
            fail(files[0], " vs ", files[1], ": ", err.what());
        }
        if (!diffPath.empty()) writeDiff(diffPath, test, ref);
        if (json) {
            std::printf(
                "{\"test\": %s, \"ref\": %s, \"width\": %d, \"height\": %d, \"channels\": %d, \"non_finite\": %zu, "
                "\"mse\": %s, \"relmse\": %s, \"relmse_epsilon\": %s, \"psnr\": %s, \"de00_mean\": %s, "
                "\"de00_p99\": %s, \"de00_max\": %s}\n",
                jsonString(files[0]).c_str(), jsonString(files[1]).c_str(), e.width, e.height, e.channels, e.nonFinite,
                jsonNumber(e.mse).c_str(), jsonNumber(e.relMse).c_str(), jsonNumber(kRelMSEEpsilon).c_str(),
                jsonNumber(e.psnr).c_str(), jsonNumber(e.meanDeltaE00).c_str(), jsonNumber(e.p99DeltaE00).c_str(),
                jsonNumber(e.maxDeltaE00).c_str());
        } else {
            std::printf("Comparing \"%s\" and \"%s\" (%dx%d, %d colour channel(s))\n", files[0].c_str(),
                        files[1].c_str(), e.width, e.height, e.channels);
            std::printf("  MSE           %.6g\n", e.mse);
            std::printf("  relMSE        %.6g  (eps = %g)\n", e.relMse, kRelMSEEpsilon);
            if (std::isinf(e.psnr)) std::printf("  PSNR          inf dB  (identical after clamping to [0,1])\n");
            else std::printf("  PSNR          %.4f dB  (values clamped to [0,1], peak 1)\n", e.psnr);
            std::printf("  dE00 mean     %.6g\n", e.meanDeltaE00);
            std::printf("  dE00 p99      %.6g\n", e.p99DeltaE00);
            std::printf("  dE00 max      %.6g\n", e.maxDeltaE00);
            if (e.nonFinite > 0) std::printf("  non-finite    %zu pixel(s) excluded\n", e.nonFinite);
        }
    } catch (const std::exception& err) {
        std::fprintf(stderr, "compare: %s\n", err.what());
        return 1;
    }
    return 0;
}
