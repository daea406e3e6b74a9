// `render`: renders a Mitsuba-XML scene to an OpenEXR file (and an sRGB PNG beside it).
// Run `render --help` for the options. Ctrl-C (SIGINT) or SIGTERM stops the render and writes
// the image with the samples done so far.
#include <atomic>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <map>
#include <string>

#include "core/error.h"
#include "render/film.h"
#include "core/io/image.h"
#include "core/source_tree.h"
#include "render/loader/scene_loader.h"
#include "render/renderer.h"
#include "render/scene.h"
#include "spectral/color_management.h"

#include <unistd.h>

using namespace iris;

namespace {

std::atomic<bool> gCancel{false};

extern "C" void onSignal(int sig) {
    gCancel.store(true);
    std::signal(sig, SIG_DFL);  // a second Ctrl-C terminates immediately
}

/// printf format: %s is the default RGB channel wavelengths.
const char* kUsage = R"(usage: render [scene.xml] [options]
Renders a scene (default: the built-in scenes/default.xml) to an OpenEXR image.

Output
  -o, --output FILE        output image (default out.exr); an .exr also gets an sRGB .png beside it
  --no-png                 do not write the .png beside the .exr
  --variance FILE          also write each pixel's estimated variance of the mean (s²/n from the
                           per-sample second moments) in CIE XYZ to the EXR FILE (channels X, Y, Z)
  --output-space NAME      colour space of the EXR (default lin_rec709; any space of the OCIO config)
  --ocio-config FILE       OpenColorIO config (default: $OCIO, else the shipped spectral/ocio/config.ocio)
  --display NAME, --view NAME   display/view for the PNG (default: the config's defaults)
Sampling
  --spp N                  samples per pixel (default: the scene's sampler sample_count)
  --time-limit SEC         stop after SEC seconds of wall time (with --spp 0: render until then)
  --seed N                 random seed (default 0); images are identical for any --threads
  --threads N              worker threads (default: all cores)
Spectral transport
  --mode spectral|rgb      spectral (default): N sampled wavelengths per path, film in CIE XYZ;
                           rgb: 3 fixed channel wavelengths, values used as linear Rec.709 RGB
  --spectral-samples N     wavelengths per path in spectral mode, 1..32 (default 4)
  --rgb-wavelengths R,G,B  channel wavelengths in nm for RGB mode (default %s)
  --uniform-wavelengths    sample wavelengths uniformly instead of by visible importance
Scene
  -D name=value            override a <default> parameter of the scene (repeatable)
Robustness
  --checkpoint FILE        keep the film state in FILE (written at the end, on Ctrl-C, and every
                           --checkpoint-every SEC); --resume continues from it bit-exactly
  --quiet                  no progress bar
  --version, --help
)";

[[noreturn]] void usageError(const std::string& msg) {
    std::fprintf(stderr, "render: %s (see render --help)\n", msg.c_str());
    std::exit(2);
}

int parseInt(const std::string& opt, const std::string& v) {
    try {
        size_t pos;
        const long long x = std::stoll(v, &pos);
        if (pos != v.size() || x < INT32_MIN || x > INT32_MAX) throw std::invalid_argument("");
        return int(x);
    } catch (...) {
        usageError("invalid value '" + v + "' for " + opt + " (expected an integer)");
    }
}

double parseDouble(const std::string& opt, const std::string& v) {
    try {
        size_t pos;
        const double x = std::stod(v, &pos);
        if (pos != v.size() || !std::isfinite(x)) throw std::invalid_argument("");
        return x;
    } catch (...) {
        usageError("invalid value '" + v + "' for " + opt + " (expected a number)");
    }
}

/// The 3x3 matrix of a linear colour-space conversion, read off OpenColorIO's images of the unit
/// vectors (columns of the matrix).
mat3 linearMap(const ColorManager& colors, const std::string& from, const std::string& to) {
    float basis[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    colors.convert(basis, 3, from, to);
    mat3 m;
    for (int k = 0; k < 3; ++k) m[k] = vec3(basis[3 * k], basis[3 * k + 1], basis[3 * k + 2]);
    return m;
}

std::string replaceExtension(const std::string& path, const std::string& ext) {
    return std::filesystem::path(path).replace_extension(ext).string();
}

}  // namespace

int main(int argc, char** argv) {
    std::string scenePath, output = "out.exr", outputSpace = kColorSpaceLinearRec709, ocioConfig, display, view;
    std::string checkpoint, variancePath;
    bool writePng = true, quiet = false, resume = false;
    std::map<std::string, std::string> defines;
    RenderOptions opt;

    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc) usageError("option " + a + " needs a value");
            return argv[++i];
        };
        if (a == "-h" || a == "--help") {
            const vec3 l = defaultChannelWavelengths();
            std::printf(kUsage, strCat(l.x, ",", l.y, ",", l.z).c_str());
            return 0;
        } else if (a == "--version") {
            std::printf("iris render %s\n", IRIS_VERSION);
            return 0;
        } else if (a == "-o" || a == "--output") output = value();
        else if (a == "--no-png") writePng = false;
        else if (a == "--variance") variancePath = value();
        else if (a == "--output-space") outputSpace = value();
        else if (a == "--ocio-config") ocioConfig = value();
        else if (a == "--display") display = value();
        else if (a == "--view") view = value();
        else if (a == "--spp") {
            opt.spp = parseInt(a, value());
            if (opt.spp < 0) usageError("--spp must be >= 0");
        } else if (a == "--time-limit") {
            opt.timeLimit = parseDouble(a, value());
            if (opt.timeLimit <= 0) usageError("--time-limit must be > 0 seconds");
        } else if (a == "--seed") {
            const int s = parseInt(a, value());
            if (s < 0) usageError("--seed must be >= 0");
            opt.seed = uint64_t(s);
        } else if (a == "--threads") {
            opt.threads = parseInt(a, value());
            if (opt.threads < 0) usageError("--threads must be >= 0");
        } else if (a == "--mode") {
            const std::string m = value();
            if (m == "rgb") opt.rgbMode = true;
            else if (m == "spectral") opt.rgbMode = false;
            else usageError("invalid value '" + m + "' for --mode (expected rgb or spectral)");
        } else if (a == "--spectral-samples") {
            opt.spectralSamples = parseInt(a, value());
            if (opt.spectralSamples < 1 || opt.spectralSamples > kMaxWavelengths)
                usageError("--spectral-samples must be in [1, " + std::to_string(kMaxWavelengths) + "]");
        } else if (a == "--rgb-wavelengths") {
            const std::string v = value();
            float l[3];
            if (std::sscanf(v.c_str(), "%f,%f,%f", &l[0], &l[1], &l[2]) != 3)
                usageError("invalid value '" + v + "' for --rgb-wavelengths (expected R,G,B in nm)");
            for (float x : l)
                if (!(x >= kLambdaMin && x <= kLambdaMax)) usageError("--rgb-wavelengths must lie in [360, 830] nm");
            opt.rgbWavelengths = vec3(l[0], l[1], l[2]);
        } else if (a == "--uniform-wavelengths") opt.uniformWavelengths = true;
        else if (a == "-D") {
            const std::string d = value();
            const size_t eq = d.find('=');
            if (eq == std::string::npos || eq == 0) usageError("-D expects name=value, got '" + d + "'");
            defines[d.substr(0, eq)] = d.substr(eq + 1);
        } else if (a.rfind("-D", 0) == 0 && a.size() > 2) {
            const std::string d = a.substr(2);
            const size_t eq = d.find('=');
            if (eq == std::string::npos || eq == 0) usageError("-D expects name=value, got '" + d + "'");
            defines[d.substr(0, eq)] = d.substr(eq + 1);
        } else if (a == "--checkpoint") checkpoint = value();
        else if (a == "--checkpoint-every") {
            opt.checkpointEvery = parseDouble(a, value());
            if (opt.checkpointEvery <= 0) usageError("--checkpoint-every must be > 0 seconds");
        } else if (a == "--resume") resume = true;
        else if (a == "--quiet" || a == "-q") quiet = true;
        else if (!a.empty() && a[0] == '-') usageError("unknown option '" + a + "'");
        else if (scenePath.empty()) scenePath = a;
        else usageError("more than one scene file given ('" + scenePath + "' and '" + a + "')");
    }
    if (scenePath.empty()) scenePath = sourcePath("scenes/default.xml");
    if ((resume || opt.checkpointEvery > 0) && checkpoint.empty()) usageError("--resume and --checkpoint-every need --checkpoint FILE");
    // An RGB-mode film keeps XYZ second moments for --variance; a checkpoint does not record that.
    if (!variancePath.empty() && !checkpoint.empty() && opt.rgbMode) usageError("--variance cannot be combined with --checkpoint in --mode rgb");
    opt.checkpointPath = checkpoint;
    opt.resume = resume;
    opt.progress = !quiet && isatty(STDERR_FILENO);

    try {
        const ColorManager colors(ocioConfig);
        if (!colors.hasColorSpace(outputSpace)) fail("--output-space: colour space '", outputSpace, "' is not in ", colors.configPath());

        SceneDescription desc = loadScene(scenePath, defines);
        const Scene scene(std::move(desc));
        const Renderer renderer(scene, opt);
        Film film(scene.description().camera.width, scene.description().camera.height);
        const std::string filmSpace = opt.rgbMode ? kColorSpaceLinearRec709 : kColorSpaceXYZ;
        if (!variancePath.empty() && opt.rgbMode) film.setMomentSpace(linearMap(colors, filmSpace, kColorSpaceXYZ));
        if (resume) film.load(checkpoint, renderer.settingsKey());

        std::signal(SIGINT, onSignal);
        std::signal(SIGTERM, onSignal);
        const RenderStats st = renderer.render(film, &gCancel);
        std::signal(SIGINT, SIG_DFL);
        std::signal(SIGTERM, SIG_DFL);

        // Film values → output colour space, through OpenColorIO.
        Image img(film.width(), film.height(), 3);
        img.pixels = film.meanImage();
        Image out = img;
        colors.convert(out.pixels.data(), out.pixelCount(), filmSpace, outputSpace);

        const ImageMetadata meta = {
            {"iris.version", IRIS_VERSION},
            {"iris.scene", scenePath},
            {"iris.mode", opt.rgbMode ? "rgb" : "spectral"},
            {"iris.spectral_samples", std::to_string(opt.rgbMode ? 3 : opt.spectralSamples)},
            {"iris.rgb_wavelengths", opt.rgbMode ? strCat(opt.rgbWavelengths.x, ",", opt.rgbWavelengths.y, ",", opt.rgbWavelengths.z) : std::string("")},
            {"iris.wavelength_pdf", opt.rgbMode ? "fixed" : (opt.uniformWavelengths ? "uniform" : "visible")},
            {"iris.spp", std::to_string(st.sppMin)},
            {"iris.spp_max", std::to_string(st.sppMax)},
            {"iris.spp_target", std::to_string(renderer.targetSpp())},
            {"iris.seed", std::to_string(opt.seed)},
            {"iris.render_time_s", strCat(st.seconds)},
            {"iris.rays", std::to_string(st.rays)},
            {"iris.invalid_samples", std::to_string(st.invalidSamples)},
            {"iris.interrupted", st.interrupted ? "1" : "0"},
            {"iris.integrator", scene.description().integrator.type},
            {"iris.max_depth", std::to_string(scene.description().integrator.maxDepth)},
            {"iris.colorspace", outputSpace},
            {"iris.ocio_config", colors.configPath()},
        };
        const bool pngOnly = std::filesystem::path(output).extension() == ".png" ||
                             std::filesystem::path(output).extension() == ".jpg";
        if (!pngOnly) writeEXR(output, out, meta);
        if (!variancePath.empty()) {
            Image var(film.width(), film.height(), 3);
            var.pixels = film.varianceOfMeanImage();
            var.channelNames = {"X", "Y", "Z"};
            writeEXR(variancePath, var, meta);
        }
        if (pngOnly || writePng) {
            Image ldr = img;
            colors.toDisplay(ldr.pixels.data(), ldr.pixelCount(), filmSpace, display, view);
            writeLDR(pngOnly ? output : replaceExtension(output, ".png"), ldr);
        }
        std::fprintf(stderr, "%s: %u spp%s in %.2f s, %.3g rays/s, %llu invalid samples%s\n", output.c_str(), st.sppMin,
                     st.sppMax != st.sppMin ? strCat(" (some pixels ", st.sppMax, ")").c_str() : "", st.seconds,
                     st.seconds > 0 ? double(st.rays) / st.seconds : 0.0, (unsigned long long)st.invalidSamples,
                     st.interrupted ? " [interrupted]" : "");
        return st.interrupted ? 130 : 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "render: error: %s\n", e.what());
        return 1;
    }
}
