// Scenes and rendering from Python. load_file / load_string go through the scene loader
// (render/loader/scene_loader.h); render runs the Renderer (render/renderer.h) on a worker thread
// with the GIL released, while the calling thread wakes every 50 ms to deliver Python signals
// (Ctrl-C → KeyboardInterrupt cancels the render, which keeps what was rendered) and to call the
// progress callback (and, with spectral_bins, a per-wavelength image: render/spectral_film.h). The image is converted and described by render/render_output.h, exactly as
// the `render` executable does, so both give the same pixels for the same scene, seed and spp.
#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <thread>

#include "apps/python/bindings.h"
#include "render/loader/scene_file.h"
#include "render/integrator.h"
#include "render/render_output.h"
#include "render/scene_hash.h"
#include "render/renderer.h"
#include "render/stokes_output.h"
#include "render/scene.h"
#include "render/scene_defaults.h"
#include "core/source_tree.h"

namespace iris::python {

namespace {

/// A loaded scene: the Embree scene is built once and can be rendered many times.
struct PyScene {
    std::string path;  // the file, or "<string>"
    std::shared_ptr<const Scene> scene;
    std::string hash;  // render/scene_hash.h for a file ("" for a string), as `render` records it
};

/// The scene's integrator type (kDefaultIntegrator, render/scene_defaults.h, when it has none).
std::string integratorType(const PyScene& s) {
    const auto& i = s.scene->description().integrator;
    return i ? i->type() : std::string(kDefaultIntegrator);
}

PyScene makeScene(const std::string& path, SceneDescription desc, std::string hash = {}) {
    py::gil_scoped_release release;  // building the Embree scene can take a while
    return {path, std::make_shared<const Scene>(std::move(desc)), std::move(hash)};
}

PyScene loadFile(const std::string& path, const std::map<std::string, std::string>& defines) {
    SceneDescription desc = loadSceneFile(path, defines);
    return makeScene(path, std::move(desc), sceneHash(path, defines));
}

PyScene loadString(const std::string& xml, const std::string& baseDir, const std::map<std::string, std::string>& defines) {
    return makeScene("<string>", loadSceneFromString(xml, baseDir, defines));
}

/// Everything a render returns to Python (the package's RenderResult is built from it).
struct RenderOutput {
    Image image;                   // in the requested colour space
    std::vector<float> variance;   // variance of each pixel's mean, in the film's space
    std::vector<uint32_t> counts;  // samples per pixel
    ImageMetadata metadata;
    RenderStats stats;
    bool keyboardInterrupt = false;  // stopped by Ctrl-C (the package raises RenderInterrupted)
    std::vector<float> spectral, spectralLambdas;  // (H, W, bins) per-wavelength image and bin centres
    std::vector<float> stokes;  // (H, W, 12): S0..S3 in the output colour space (the stokes integrator)
};

/// Renders on a worker thread; the caller (holding the GIL) polls signals and progress.
class BackgroundRender {
public:
    BackgroundRender(const Renderer& renderer, Film& film, SpectralFilm* spectral, StokesFilm* stokes)
        : thread_([this, &renderer, &film, spectral, stokes] {
        try {
            stats_ = renderer.render(film, &cancel_, spectral, stokes);
        } catch (...) {
            error_ = std::current_exception();
        }
        std::lock_guard lock(mutex_);
        done_ = true;
        wake_.notify_all();
    }) {}
    ~BackgroundRender() {
        cancel_ = true;
        if (thread_.joinable()) thread_.join();
    }
    /// Waits up to `ms` without the GIL; true when the render has finished.
    bool waitFor(int ms) {
        py::gil_scoped_release release;
        std::unique_lock lock(mutex_);
        return wake_.wait_for(lock, std::chrono::milliseconds(ms), [this] { return done_; });
    }
    void cancel() { cancel_ = true; }
    RenderStats finish() {
        {
            py::gil_scoped_release release;
            thread_.join();
        }
        if (error_) std::rethrow_exception(error_);
        return stats_;
    }

private:
    std::atomic<bool> cancel_{false};
    std::mutex mutex_;
    std::condition_variable wake_;
    bool done_ = false;
    RenderStats stats_;
    std::exception_ptr error_;
    std::thread thread_;  // last: starts after the members above exist
};

RenderOutput render(const PyScene& s, RenderOptions opt, int spectralBins, const std::string& outputSpace,
                    const std::string& ocioConfig, const py::object& progress) {
    const ColorManager colors(ocioConfig);
    if (!colors.hasColorSpace(outputSpace))
        fail("colorspace: '", outputSpace, "' is not in ", colors.configPath());
    std::atomic<double> fraction{0.0};
    opt.progressOut = &fraction;
    opt.progress = false;
    opt.sceneHash = s.hash;
    const Renderer renderer(*s.scene, opt);
    const CameraDescription& cam = s.scene->description().camera;
    Film film(cam.width, cam.height);
    std::unique_ptr<SpectralFilm> spectral;
    // spectral_bins = B equal bins over 360-830 nm (SpectralBins takes their width).
    if (spectralBins > 0)
        spectral = std::make_unique<SpectralFilm>(cam.width, cam.height, SpectralBins((kLambdaMax - kLambdaMin) / double(spectralBins)));
    // Polarized mode with Mitsuba 3's stokes integrator: its S0..S3 channels (as render writes them).
    std::unique_ptr<StokesFilm> stokes;
    if (opt.polarized && integratorType(s) == "stokes") stokes = std::make_unique<StokesFilm>(cam.width, cam.height);

    RenderOutput out;
    std::unique_ptr<py::error_already_set> pythonError;  // raised by the progress callback or a signal handler
    {
        BackgroundRender job(renderer, film, spectral.get(), stokes.get());
        bool finished = false;
        while (!finished) {
            finished = job.waitFor(50);
            if (PyErr_CheckSignals() != 0) {
                job.cancel();
                if (PyErr_ExceptionMatches(PyExc_KeyboardInterrupt)) {
                    PyErr_Clear();
                    out.keyboardInterrupt = true;
                } else {
                    pythonError = std::make_unique<py::error_already_set>();
                }
            }
            if (!progress.is_none() && !pythonError) {
                try {
                    progress(finished ? 1.0 : std::min(1.0, fraction.load()));
                } catch (py::error_already_set& e) {
                    job.cancel();
                    pythonError = std::make_unique<py::error_already_set>(std::move(e));
                }
            }
        }
        out.stats = job.finish();
    }
    if (pythonError) throw std::move(*pythonError);
    out.image = filmImage(film, opt.rgbMode, colors, outputSpace);
    out.variance = film.varianceOfMeanImage();
    out.counts.resize(size_t(film.width()) * film.height());
    for (int y = 0; y < film.height(); ++y)
        for (int x = 0; x < film.width(); ++x) out.counts[size_t(y) * film.width() + x] = film.sampleCount(x, y);
    if (spectral) {
        out.spectral = spectral->image().pixels;
        for (int b = 0; b < spectral->bins().count(); ++b) out.spectralLambdas.push_back(float(spectral->bins().centre(b)));
    }
    if (stokes) out.stokes = stokesImage(*stokes, colors, outputSpace).pixels;
    out.metadata = renderMetadata(*s.scene, s.path, renderer, opt, out.stats, colors, outputSpace);
    return out;
}

py::dict renderToPython(const PyScene& s, int spp, double timeLimit, uint64_t seed, int threads, bool rgbMode, bool polarized,
                        int spectralSamples, const std::vector<float>& rgbWavelengths, bool uniformWavelengths,
                        bool independentWavelengths, const std::string& sampler, int spectralBins, const std::string& outputSpace,
                        const std::string& ocioConfig, const py::object& progress) {
    RenderOptions opt;
    opt.spp = spp;
    opt.patternSize = std::max(spp, 0);  // as render --spp N: the sample count is the pattern size
    opt.sampler = sampler;
    opt.timeLimit = timeLimit;
    opt.seed = seed;
    opt.threads = threads;
    opt.rgbMode = rgbMode;
    opt.polarized = polarized;
    opt.spectralSamples = spectralSamples;
    if (!rgbWavelengths.empty()) opt.rgbWavelengths = vec3(rgbWavelengths[0], rgbWavelengths[1], rgbWavelengths[2]);
    opt.uniformWavelengths = uniformWavelengths;
    opt.independentWavelengths = independentWavelengths;
    RenderOutput r = render(s, opt, spectralBins, outputSpace, ocioConfig, progress);
    const py::ssize_t h = r.image.height, w = r.image.width;
    py::dict d;
    d["image"] = ownedArray(std::move(r.image.pixels), {h, w, 3});
    d["variance"] = ownedArray(std::move(r.variance), {h, w, 3});
    d["sample_count"] = ownedArray(std::move(r.counts), {h, w});
    if (spectralBins > 0) {
        const py::ssize_t bins = py::ssize_t(r.spectralLambdas.size());
        d["spectral"] = ownedArray(std::move(r.spectral), {h, w, bins});
        d["spectral_wavelengths"] = ownedArray(std::move(r.spectralLambdas), {bins});
    }
    if (!r.stokes.empty()) d["stokes"] = ownedArray(std::move(r.stokes), {h, w, py::ssize_t(12)});
    py::dict meta;
    for (const auto& [k, v] : r.metadata) meta[py::str(k)] = v;
    d["metadata"] = meta;
    py::dict stats;
    stats["seconds"] = r.stats.seconds;
    stats["rays"] = r.stats.rays;
    stats["paths"] = r.stats.paths;
    stats["invalid_samples"] = r.stats.invalidSamples;
    stats["spp_min"] = r.stats.sppMin;
    stats["spp_max"] = r.stats.sppMax;
    stats["interrupted"] = r.stats.interrupted;
    stats["time_limited"] = r.stats.timeLimited;
    d["stats"] = stats;
    d["keyboard_interrupt"] = r.keyboardInterrupt;
    return d;
}

}  // namespace

void bindRender(py::module_& m) {
    py::class_<PyScene>(m, "Scene")
        .def_readonly("path", &PyScene::path)
        .def_property_readonly("width", [](const PyScene& s) { return s.scene->description().camera.width; })
        .def_property_readonly("height", [](const PyScene& s) { return s.scene->description().camera.height; })
        .def_property_readonly("spp", [](const PyScene& s) { return s.scene->description().spp; })
        .def_property_readonly("integrator", [](const PyScene& s) { return integratorType(s); })
        .def_property_readonly("max_depth", [](const PyScene& s) { const auto& i = s.scene->description().integrator; return i ? i->maxDepth() : -1; })
        .def_property_readonly("triangle_count", [](const PyScene& s) { return s.scene->triangleCount(); })
        .def_property_readonly("light_count", [](const PyScene& s) { return s.scene->lights().size(); })
        .def("__repr__", [](const PyScene& s) {
            const auto& d = s.scene->description();
            return strCat("<iris.Scene '", s.path, "' ", d.camera.width, "x", d.camera.height, ", ", s.scene->triangleCount(),
                          " triangles, ", s.scene->lights().size(), " lights, integrator ", integratorType(s), ">");
        });
    m.def("load_file", &loadFile, py::arg("path"), py::arg("defines"));
    m.def("load_string", &loadString, py::arg("xml"), py::arg("base_dir"), py::arg("defines"));
    m.def("render", &renderToPython, py::arg("scene"), py::arg("spp"), py::arg("time_limit"), py::arg("seed"),
          py::arg("threads"), py::arg("rgb_mode"), py::arg("polarized"), py::arg("spectral_samples"), py::arg("rgb_wavelengths"),
          py::arg("uniform_wavelengths"), py::arg("independent_wavelengths"), py::arg("sampler"), py::arg("spectral_bins"), py::arg("colorspace"), py::arg("ocio_config"), py::arg("progress"));
    m.def("source_path", &sourcePath, py::arg("relative"));
}

}  // namespace iris::python
