// `render`: renders a Mitsuba-XML scene to an OpenEXR file (and an sRGB PNG beside it).
// Run `render --help` for the options. Ctrl-C (SIGINT) or SIGTERM stops the render and writes
// the image with the samples done so far.
#include <algorithm>
#include <atomic>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <iostream>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"
#include "core/memory_budget.h"
#include "render/film.h"
#include "core/io/image.h"
#include "core/io/output_file.h"
#include "core/io/spectral_layout.h"
#include "core/source_tree.h"
#include "render/loader/scene_file.h"
#include "render/render_output.h"
#include "render/integrator.h"
#include "render/renderer.h"
#include "render/scene.h"
#include "render/samplers/sampler_description.h"
#include "render/scene_hash.h"
#include "render/stokes_film.h"
#include "render/stokes_output.h"
#include "spectral/color_management.h"

#include <unistd.h>

using namespace iris;

namespace {

std::atomic<bool> gCancel{false};

extern "C" void onSignal(int sig) {
    gCancel.store(true);
    std::signal(sig, SIG_DFL);  // a second Ctrl-C terminates immediately
}

/// Test hook (docs/testing.md, "Fault hooks"): IRIS_TEST_SIGNAL_AFTER_PASSES=K or
/// IRIS_TEST_SIGNAL_AFTER_TILES=K raise IRIS_TEST_SIGNAL (INT, the default, or TERM) once K passes
/// or K tiles of this run are finished, so that interruption tests do not race the render.
std::function<void(uint64_t, int)> signalHookFromEnvironment() {
    auto count = [](const char* name) -> uint64_t {
        const char* v = std::getenv(name);
        if (!v || !*v) return 0;
        char* end = nullptr;
        const unsigned long long n = std::strtoull(v, &end, 10);
        if (*end != '\0' || n == 0) fail(name, " must be a positive integer, got '", v, "'");
        return n;
    };
    const uint64_t passes = count("IRIS_TEST_SIGNAL_AFTER_PASSES"), tiles = count("IRIS_TEST_SIGNAL_AFTER_TILES");
    if (!passes && !tiles) return {};
    const char* name = std::getenv("IRIS_TEST_SIGNAL");
    const std::string sigName = name ? name : "INT";
    if (sigName != "INT" && sigName != "TERM") fail("IRIS_TEST_SIGNAL must be INT or TERM, got '", sigName, "'");
    const int sig = sigName == "INT" ? SIGINT : SIGTERM;
    return [=](uint64_t finished, int tilesPerPass) {
        if (finished == (passes ? passes * uint64_t(tilesPerPass) : tiles)) std::raise(sig);
    };
}

/// Test hook: IRIS_TEST_SIGNAL_AT_START=1 raises IRIS_TEST_SIGNAL (INT or TERM) before the scene is
/// loaded (start-up and table builds run with the default signal actions: the process ends and
/// writes nothing).
void raiseAtStartIfAsked() {
    const char* v = std::getenv("IRIS_TEST_SIGNAL_AT_START");
    if (!v || std::string(v) != "1") return;
    const char* name = std::getenv("IRIS_TEST_SIGNAL");
    std::raise(name && std::string(name) == "TERM" ? SIGTERM : SIGINT);
}

/// printf format: %s is the default RGB channel wavelengths.
const char* kUsage = R"(usage: render [scene.xml] [options]
Renders a scene (default: the built-in scenes/default.xml) to an OpenEXR image.

Output
  -o, --output FILE        output image (default out.exr); an .exr also gets an sRGB .png beside it.
                           Every output path is checked before the scene is loaded; an output
                           whose final write fails goes to iris-rescued-<pid>-<name> in the
                           current folder or $TMPDIR, which the error names
  --no-png                 do not write the .png beside the .exr
  --variance FILE          also write each pixel's estimated variance of the mean (s²/n from the
                           per-sample second moments) in CIE XYZ to the EXR FILE (channels X, Y, Z)
  --output-space NAME      colour space of the EXR (default lin_rec709; any space of the OCIO config)
  --ocio-config FILE       OpenColorIO config (default: $OCIO, else the shipped spectral/ocio/config.ocio)
  --display NAME, --view NAME   display/view for the PNG (default: the config's defaults)
  --spectral-output FILE   also write the spectral radiance (spectral mode) to FILE.exr in the
                           OpenEXR spectral layout of Fichet et al. 2021: one channel S0.<nm>nm
                           per bin, the mean radiance over the bin (docs/spectral.md)
  --spectral-bin-width NM  bin width for --spectral-output over 360-830 nm (default 5)
Sampling
  --spp N                  samples per pixel (default: the scene's sampler sample_count); also the
                           pattern size of the stratified and multijitter samplers
  --spp-range A:B          render only samples A..B-1 of every pixel (a shard of a split render);
                           keep its film state with --checkpoint and add the shards with `merge`;
                           give the whole render's --spp too when the sampler is stratified or
                           multijitter (the pattern size the shards share)
  --sampler NAME           independent, stratified, multijitter, sobol or highdimsobol
                           (default: the scene's <sampler>); docs/rendering.md says how each
                           draws its points
  --time-limit SEC         stop after SEC seconds of wall time (with --spp 0: render until then)
  --seed N                 random seed (default 0); images are identical for any --threads
  --threads N              worker threads (default: all cores)
Spectral transport
  --mode spectral|rgb|polarized
                           spectral (default): N sampled wavelengths per path, film in CIE XYZ;
                           rgb: 3 fixed channel wavelengths, values used as linear Rec.709 RGB;
                           polarized: spectral with a Stokes vector per wavelength and Mueller
                           matrices at every interaction, the image is S0 (docs/polarization.md;
                           the default for a scene whose integrator is Mitsuba 3's stokes, which
                           adds the channels S0.R ... S3.B)
  --spectral-samples N     wavelengths per path in spectral mode, 1..32 (default 4)
  --rgb-wavelengths R,G,B  channel wavelengths in nm for RGB mode (default %s)
  --uniform-wavelengths    sample wavelengths uniformly instead of by visible importance
  --wavelength-sampling hero|independent
                           hero (default): N stratified rotations of one sample (Wilkie et al.
                           2014); independent: N independent wavelengths (ablation)
Scene
  -D name=value            override a <default> parameter of the scene (repeatable); for a
                           glTF scene: res, width, height, spp, rgb_mode (docs/gltf.md)
  --camera NAME            glTF scenes: the camera (or its node) called NAME, not the first one
  --envmap FILE            glTF scenes: light the scene by this environment map
Robustness
  --checkpoint FILE        keep the film state in FILE (written at the end, on Ctrl-C, and every
                           --checkpoint-every SEC); --resume continues from it bit-exactly
  --memory-limit SIZE      refuse a scene whose parsed XML, meshes, textures, volumes, film and
                           ray-tracing geometry would need more than SIZE (e.g. 512M, 4G; binary
                           units; 0: no limit), before allocating them; also IRIS_MEMORY_LIMIT;
                           default: half of the memory the process may use (physical memory, or
                           less under a cgroup limit or ulimit -v)
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

/// The image plus Mitsuba's moment AOVs: moment1.{R,G,B} (the per-pixel mean) and moment2.{R,G,B}
/// (the mean of the squared samples), both in the film's space (XYZ in spectral mode, linear
/// Rec.709 in RGB mode): a second moment does not transform linearly between colour spaces.
Image withMoments(const Image& img, const Film& film) {
    const std::vector<float> m1 = film.meanImage(), m2 = film.secondMomentImage();
    Image out(img.width, img.height, 9);
    out.channelNames = {"R", "G", "B", "moment1.R", "moment1.G", "moment1.B", "moment2.R", "moment2.G", "moment2.B"};
    for (size_t p = 0; p < img.pixelCount(); ++p)
        for (int c = 0; c < 3; ++c) {
            out.pixels[9 * p + c] = img.pixels[3 * p + c];
            out.pixels[9 * p + 3 + c] = m1[3 * p + c];
            out.pixels[9 * p + 6 + c] = m2[3 * p + c];
        }
    return out;
}

/// Every path the run will write, checked before the scene is loaded (core/io/output_file.h): a
/// bad one is a usage error, found in a second instead of after the render.
void checkOutputPaths(const std::vector<std::pair<std::string, std::string>>& outputs) {
    for (const auto& [option, path] : outputs) {
        if (path.empty()) continue;
        try {
            checkOutputPath(path, option);
        } catch (const Error& e) {
            usageError(e.what());
        }
    }
}

/// Write one output through `write`, to a fallback path if its own fails; a failure is added to
/// `errors` (one line each) so that the other outputs are still written.
void writeOrRescue(const std::string& path, const std::function<void(const std::string&)>& write, std::string& errors) {
    try {
        writeWithFallback(path, write);
    } catch (const Error& e) {
        errors += strCat(errors.empty() ? "" : "\n", "render: error: ", e.what());
    }
}

}  // namespace

int main(int argc, char** argv) {
    std::string scenePath, output = "out.exr", outputSpace = kColorSpaceLinearRec709, ocioConfig, display, view;
    std::string checkpoint, spectralOutput, variancePath;
    double spectralBinWidth = 5.0;
    bool writePng = true, quiet = false, resume = false, sppRange = false, modeGiven = false;
    int sppArg = -1, rangeEnd = 0;  // --spp, and the end of --spp-range
    std::map<std::string, std::string> defines;
    GltfOptions gltfOptions;
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
        else if (a == "--spectral-output") spectralOutput = value();
        else if (a == "--spectral-bin-width") {
            spectralBinWidth = parseDouble(a, value());
            if (!(spectralBinWidth > 0)) usageError("--spectral-bin-width must be > 0 nm");
        }
        else if (a == "--spp") {
            sppArg = parseInt(a, value());
            if (sppArg < 0) usageError("--spp must be >= 0");
        } else if (a == "--spp-range") {
            const std::string v = value();
            const size_t colon = v.find(':');
            if (colon == std::string::npos) usageError("invalid value '" + v + "' for --spp-range (expected A:B)");
            const int b = parseInt(a, v.substr(0, colon)), e = parseInt(a, v.substr(colon + 1));
            if (b < 0 || e <= b) usageError("--spp-range A:B needs 0 <= A < B, got '" + v + "'");
            opt.firstSample = b;
            rangeEnd = e;
            sppRange = true;
        } else if (a == "--sampler") {
            opt.sampler = value();
            try {
                sampleSequenceNamed(opt.sampler);
            } catch (const Error& e) {
                usageError(e.what());
            }
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
            modeGiven = true;
            if (m == "rgb") opt.rgbMode = true, opt.polarized = false;
            else if (m == "spectral") opt.rgbMode = false, opt.polarized = false;
            else if (m == "polarized") opt.rgbMode = false, opt.polarized = true;
            else usageError("invalid value '" + m + "' for --mode (expected rgb, spectral or polarized)");
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
        else if (a == "--wavelength-sampling") {
            const std::string m = value();
            if (m == "hero") opt.independentWavelengths = false;
            else if (m == "independent") opt.independentWavelengths = true;
            else usageError("invalid value '" + m + "' for --wavelength-sampling (expected hero or independent)");
        }
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
        else if (a == "--memory-limit") {
            const std::string v = value();
            try {
                setMemoryLimit(parseByteSize(v));
            } catch (const Error& e) {
                usageError(std::string("--memory-limit: ") + e.what());
            }
        }
        else if (a == "--quiet" || a == "-q") quiet = true;
        else if (a == "--camera") gltfOptions.camera = value();
        else if (a == "--envmap") gltfOptions.envmap = value();
        else if (!a.empty() && a[0] == '-') usageError("unknown option '" + a + "'");
        else if (scenePath.empty()) scenePath = a;
        else usageError("more than one scene file given ('" + scenePath + "' and '" + a + "')");
    }
    if (scenePath.empty()) scenePath = sourcePath("scenes/default.xml");
    // --spp N is the render's sample count and its sampler's pattern size; with --spp-range A:B it
    // names the whole render the shard belongs to (its pattern size), in any order of the options.
    opt.spp = sppRange ? rangeEnd - opt.firstSample : sppArg;
    opt.patternSize = std::max(sppArg, 0);
    if ((resume || opt.checkpointEvery > 0) && checkpoint.empty()) usageError("--resume and --checkpoint-every need --checkpoint FILE");
    if (!spectralOutput.empty() && opt.rgbMode) usageError("--spectral-output needs --mode spectral (RGB-mode channels are not wavelength samples)");
    if (!spectralOutput.empty() && resume) usageError("--spectral-output cannot be combined with --resume (checkpoints hold the colour film only)");
    if (sppRange && checkpoint.empty()) usageError("--spp-range needs --checkpoint FILE (the film state that `merge` adds up)");
    // An RGB-mode film keeps XYZ second moments for --variance; a checkpoint does not record that.
    if (!variancePath.empty() && !checkpoint.empty() && opt.rgbMode) usageError("--variance cannot be combined with --checkpoint in --mode rgb");
    if (sppArg == 0 && !sppRange && !(opt.timeLimit > 0)) usageError("--spp 0 needs --time-limit SEC (it renders until then)");
    const bool pngOnly = std::filesystem::path(output).extension() == ".png" || std::filesystem::path(output).extension() == ".jpg";
    const std::string ldrPath = pngOnly ? output : writePng ? replaceExtension(output, ".png") : "";
    checkOutputPaths({{"-o", output}, {"-o (the .png beside it)", pngOnly ? "" : ldrPath}, {"--spectral-output", spectralOutput},
                      {"--variance", variancePath}, {"--checkpoint", checkpoint}});
    opt.checkpointPath = checkpoint;
    opt.resume = resume;
    opt.progress = !quiet && isatty(STDERR_FILENO);

    try {
        const ColorManager colors(ocioConfig);
        if (!colors.hasColorSpace(outputSpace))  // a usage error, refused before any work like the others
            usageError(strCat("--output-space: colour space '", outputSpace, "' is not in ", colors.configPath()));

        memoryLimit();  // an invalid IRIS_MEMORY_LIMIT stops here, before the scene is read
        raiseAtStartIfAsked();
        SceneDescription desc = loadSceneFile(scenePath, defines, gltfOptions);
        opt.sceneHash = sceneHash(scenePath, defines);  // after the loader, whose errors name file:line
        // A scene that asks for Mitsuba 3's stokes integrator renders polarized unless --mode says otherwise.
        if (!modeGiven && desc.integrator && desc.integrator->type() == "stokes") opt.polarized = true;
        const bool stokesOutput = opt.polarized && desc.integrator && desc.integrator->type() == "stokes";
        if (stokesOutput && !checkpoint.empty()) fail("the stokes integrator's channels are not kept in checkpoints: drop --checkpoint");
        const Scene scene(std::move(desc));
        opt.onTileFinished = signalHookFromEnvironment();
        const Renderer renderer(scene, opt);
        Film film(scene.description().camera.width, scene.description().camera.height);
        const std::string filmSpace = filmColorSpace(opt.rgbMode);
        if (!variancePath.empty() && opt.rgbMode) film.setMomentSpace(linearMap(colors, filmSpace, kColorSpaceXYZ));
        if (resume) film.load(checkpoint, renderer.settingsKey());
        std::optional<SpectralFilm> spectral;
        if (!spectralOutput.empty()) spectral.emplace(film.width(), film.height(), SpectralBins(spectralBinWidth));

        std::optional<StokesFilm> stokes;
        if (stokesOutput) stokes.emplace(film.width(), film.height());

        std::signal(SIGINT, onSignal);
        std::signal(SIGTERM, onSignal);
        const RenderStats st = renderer.render(film, &gCancel, spectral ? &*spectral : nullptr, stokes ? &*stokes : nullptr);
        std::signal(SIGINT, SIG_DFL);
        std::signal(SIGTERM, SIG_DFL);

        // Film values → output colour space, through OpenColorIO (render/render_output.h).
        const Image out = filmImage(film, opt.rgbMode, colors, outputSpace);
        const ImageMetadata meta = renderMetadata(scene, scenePath, renderer, opt, st, colors, outputSpace);
        std::string errors;  // outputs that could not be written where asked (each was rescued or reported)
        if (!pngOnly) {
            const Image main = scene.description().integrator->type() == "moment" ? withMoments(out, film) : out;
            const Image exr = stokes ? appendChannels(main, stokesImage(*stokes, colors, outputSpace)) : main;
            writeOrRescue(output, [&](const std::string& p) { writeEXR(p, exr, meta); }, errors);
        }
        if (spectral) {
            ImageMetadata spectralMeta = spectralLayoutMetadata();
            spectralMeta.insert(spectralMeta.end(), meta.begin(), meta.end());
            spectralMeta.emplace_back("iris.spectral_bin_width_nm", strCat(spectralBinWidth));
            writeOrRescue(spectralOutput, [&](const std::string& p) { writeEXR(p, spectral->image(), spectralMeta); }, errors);
        }
        if (!variancePath.empty()) {
            Image var(film.width(), film.height(), 3);
            var.pixels = film.varianceOfMeanImage();
            var.channelNames = {"X", "Y", "Z"};
            writeOrRescue(variancePath, [&](const std::string& p) { writeEXR(p, var, meta); }, errors);
        }
        if (!ldrPath.empty()) {
            Image ldr(film.width(), film.height(), 3);
            ldr.pixels = film.meanImage();
            if (const auto& tonemap = scene.description().camera.ldr) {  // an ldrfilm: its own tone map
                colors.convert(ldr.pixels.data(), ldr.pixelCount(), filmSpace, kColorSpaceLinearRec709);
                applyLdrTonemap(*tonemap, ldr.pixels.data(), ldr.pixelCount());
            } else {
                colors.toDisplay(ldr.pixels.data(), ldr.pixelCount(), filmSpace, display, view);
            }
            writeOrRescue(ldrPath, [&](const std::string& p) { writeLDR(p, ldr); }, errors);
        }
        if (!st.checkpointError.empty()) errors += (errors.empty() ? "" : "\n") + ("--checkpoint " + st.checkpointError);
        if (!errors.empty()) {  // one line per output that is not where it was asked
            std::fprintf(stderr, "%s\n", errors.c_str());
            return 1;
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
