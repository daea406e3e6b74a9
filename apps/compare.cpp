// compare: error metrics of a test image against a reference (like OpenImageIO's idiff).
//   compare test.exr ref.exr [--json] [--diff out.exr|out.png] [--per-channel] [--no-flip] [--ppd P]
// Prints MSE, relMSE, SMAPE, PSNR, mean / p99 / max CIEDE2000, mean LDR- and HDR-FLIP (definitions
// in docs/metrics.md); exit 0. A spectral image (render --spectral-output) is compared in linear
// Rec.709 derived from its bins, and --per-channel gives the error of every wavelength band.
// Errors (unreadable file, size mismatch, bad arguments) print one line and exit 1.
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/io/image.h"
#include "core/io/spectral_layout.h"
#include "metrics/flip.h"
#include "metrics/image_metrics.h"
#include "spectral/color_space.h"
#include "spectral/spectral_bins.h"

using namespace iris;

namespace {

const char* kUsage =
    "usage: compare test.exr ref.exr [--json] [--diff out.exr|out.png] [--per-channel] [--no-flip] [--ppd P]\n"
    "  --json          print the metrics as one JSON object\n"
    "  --diff FILE     write test-ref (R,G,B), the per-pixel CIEDE2000 (channel dE00) and HDR-FLIP\n"
    "                  (channel FLIP) to an EXR, or the CIEDE2000 map scaled by 1/10 (white = 10) to\n"
    "                  an 8-bit PNG/JPEG\n"
    "  --per-channel   also MSE, relMSE and SMAPE of every channel both images have (e.g. the\n"
    "                  wavelength bands S0.<nm>nm of spectral images; the other metrics compare a\n"
    "                  spectral image through the linear Rec.709 colour derived from its bins)\n"
    "  --no-flip       skip LDR-/HDR-FLIP (the slowest metrics)\n"
    "  --ppd P         pixels per degree for FLIP (default 67.02: 0.7 m from a 0.7 m wide 3840-pixel monitor)\n";

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

/// `flipMap` is empty with --no-flip.
void writeDiff(const std::string& path, const Image& test, const Image& ref, const Image& flipMap) {
    const Image diff = differenceImage(test, ref);
    const Image de = deltaE00Map(test, ref);
    if (endsWith(path, ".exr")) {
        std::vector<const Image*> parts = {&diff, &de};
        if (!flipMap.pixels.empty()) parts.push_back(&flipMap);
        Image out(diff.width, diff.height, diff.channels + int(parts.size()) - 1);
        out.channelNames = diff.channels == 3 ? std::vector<std::string>{"R", "G", "B", "dE00"}
                                              : std::vector<std::string>{"Y", "dE00"};
        if (!flipMap.pixels.empty()) out.channelNames.push_back("FLIP");
        for (size_t p = 0; p < diff.pixelCount(); ++p) {
            size_t c = 0;
            for (const Image* part : parts)
                for (int k = 0; k < part->channels; ++k)
                    out.pixels[p * size_t(out.channels) + c++] = part->pixels[p * size_t(part->channels) + size_t(k)];
        }
        writeEXR(path, out, {{"iris.compare.test", "test-ref"}});
    } else {
        Image out(de.width, de.height, 3);
        for (size_t p = 0; p < de.pixelCount(); ++p)
            for (int c = 0; c < 3; ++c) out.pixels[3 * p + size_t(c)] = std::isfinite(de.pixels[p]) ? de.pixels[p] / 10.0f : 1.0f;
        writeLDR(path, out);
    }
}

/// The colour image the metrics compare: a spectral image (Fichet et al. 2021 layout) becomes
/// linear Rec.709 through CIE XYZ (what `render` writes by default); any other image is as read.
Image colourImage(const Image& img, const std::string& path) {
    if (!hasSpectralChannels(img)) return img;
    Image rgb = xyzImage(spectralChannels(img, path));
    rgb.channelNames = {"R", "G", "B"};
    for (size_t p = 0; p < rgb.pixelCount(); ++p) {
        const dvec3 c = xyzToLinearRec709(dvec3(rgb.pixels[3 * p], rgb.pixels[3 * p + 1], rgb.pixels[3 * p + 2]));
        for (int k = 0; k < 3; ++k) rgb.pixels[3 * p + size_t(k)] = float(c[k]);
    }
    return rgb;
}

std::string jsonChannels(const std::vector<ChannelErrors>& channels) {
    std::string out = "[";
    for (const ChannelErrors& c : channels)
        out += std::string(out.size() > 1 ? ", " : "") + "{\"name\": " + jsonString(c.name) + ", \"count\": " +
               std::to_string(c.count) + ", \"mse\": " + jsonNumber(c.mse) + ", \"relmse\": " + jsonNumber(c.relMse) +
               ", \"smape\": " + jsonNumber(c.smape) + "}";
    return out + "]";
}

}  // namespace

int main(int argc, char** argv) {
    std::vector<std::string> files;
    bool json = false, perChannel = false, withFlip = true;
    double ppd = flip::pixelsPerDegree();
    std::string diffPath;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--json") json = true;
        else if (a == "--per-channel") perChannel = true;
        else if (a == "--no-flip") withFlip = false;
        else if (a == "--ppd") {
            char* end = nullptr;
            ppd = i + 1 < argc ? std::strtod(argv[++i], &end) : 0.0;
            if (!end || *end != '\0' || !(ppd > 0) || !std::isfinite(ppd)) {
                std::fprintf(stderr, "compare: --ppd needs a positive number\n%s", kUsage);
                return 1;
            }
        } else if (a == "--diff") {
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
        const Image testFile = readImage(files[0]);
        const Image refFile = readImage(files[1]);
        const Image test = colourImage(testFile, files[0]);
        const Image ref = colourImage(refFile, files[1]);
        ImageErrors e;
        try {
            e = compareImages(test, ref);
        } catch (const Error& err) {
            fail(files[0], " vs ", files[1], ": ", err.what());
        }
        FlipResult ldr, hdr;
        if (withFlip) {
            ldr = ldrFlip(test, ref, ppd);
            hdr = hdrFlip(test, ref, ppd);
        }
        const double nan = std::nan("");
        const std::vector<ChannelErrors> channels = perChannel ? channelErrors(testFile, refFile) : std::vector<ChannelErrors>{};
        if (!diffPath.empty()) writeDiff(diffPath, test, ref, hdr.map);
        if (json) {
            std::printf(
                "{\"test\": %s, \"ref\": %s, \"width\": %d, \"height\": %d, \"channels\": %d, \"non_finite\": %zu, "
                "\"mse\": %s, \"relmse\": %s, \"relmse_epsilon\": %s, \"smape\": %s, \"smape_epsilon\": %s, "
                "\"psnr\": %s, \"de00_mean\": %s, \"de00_p99\": %s, \"de00_max\": %s, \"flip_ldr_mean\": %s, "
                "\"flip_hdr_mean\": %s, \"flip_ppd\": %s, \"flip_hdr_exposures\": [%s, %s, %d]%s}\n",
                jsonString(files[0]).c_str(), jsonString(files[1]).c_str(), e.width, e.height, e.channels, e.nonFinite,
                jsonNumber(e.mse).c_str(), jsonNumber(e.relMse).c_str(), jsonNumber(kRelMSEEpsilon).c_str(),
                jsonNumber(e.smape).c_str(), jsonNumber(kSmapeEpsilon).c_str(), jsonNumber(e.psnr).c_str(),
                jsonNumber(e.meanDeltaE00).c_str(), jsonNumber(e.p99DeltaE00).c_str(), jsonNumber(e.maxDeltaE00).c_str(),
                jsonNumber(withFlip ? ldr.mean : nan).c_str(), jsonNumber(withFlip ? hdr.mean : nan).c_str(),
                jsonNumber(ppd).c_str(), jsonNumber(hdr.exposures.start).c_str(), jsonNumber(hdr.exposures.stop).c_str(),
                hdr.exposures.count, perChannel ? (", \"per_channel\": " + jsonChannels(channels)).c_str() : "");
        } else {
            std::printf("Comparing \"%s\" and \"%s\" (%dx%d, %d colour channel(s))\n", files[0].c_str(),
                        files[1].c_str(), e.width, e.height, e.channels);
            std::printf("  MSE           %.6g\n", e.mse);
            std::printf("  relMSE        %.6g  (eps = %g)\n", e.relMse, kRelMSEEpsilon);
            std::printf("  SMAPE         %.6g  (eps = %g)\n", e.smape, kSmapeEpsilon);
            if (std::isinf(e.psnr)) std::printf("  PSNR          inf dB  (identical after clamping to [0,1])\n");
            else std::printf("  PSNR          %.4f dB  (values clamped to [0,1], peak 1)\n", e.psnr);
            std::printf("  dE00 mean     %.6g\n", e.meanDeltaE00);
            std::printf("  dE00 p99      %.6g\n", e.p99DeltaE00);
            std::printf("  dE00 max      %.6g\n", e.maxDeltaE00);
            if (withFlip) {
                std::printf("  LDR-FLIP mean %.6g  (%.4g pixels per degree)\n", ldr.mean, ppd);
                std::printf("  HDR-FLIP mean %.6g  (%d exposures, %.4g .. %.4g stops)\n", hdr.mean, hdr.exposures.count,
                            hdr.exposures.start, hdr.exposures.stop);
            }
            for (const ChannelErrors& c : channels)
                std::printf("  channel %-12s MSE %.6g  relMSE %.6g  SMAPE %.6g\n", c.name.c_str(), c.mse, c.relMse, c.smape);
            if (e.nonFinite > 0) std::printf("  non-finite    %zu pixel(s) excluded\n", e.nonFinite);
        }
    } catch (const std::exception& err) {
        std::fprintf(stderr, "compare: %s\n", err.what());
        return 1;
    }
    return 0;
}
