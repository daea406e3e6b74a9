#include "render/renderer.h"

#include "core/io/output_file.h"

#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <mutex>
#include <optional>
#include <thread>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include "core/error.h"
#include "core/io/output_file.h"
#include "core/tsan_fork_join.h"
#include "render/integrator.h"
#include "render/polarized_sample.h"
#include "render/samplers/sampler_description.h"
#include "render/splat_film.h"
#include "render/stokes_film.h"
#include "spectral/xyz.h"
#include "render/scene_defaults.h"

namespace iris {

namespace {
constexpr int kTile = 16;
using Clock = std::chrono::steady_clock;

/// --wavelength-sampling independent: one primary sample per wavelength, drawn in order.
SampledWavelengths independentWavelengths(Sampler& sampler, const RenderOptions& opt) {
    float u[kMaxWavelengths];
    for (int i = 0; i < opt.spectralSamples; ++i) u[i] = sampler.get1D();
    return SampledWavelengths::sampleIndependent(u, opt.spectralSamples, opt.uniformWavelengths);
}

double secondsSince(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

/// Prints "[=====>    ] 45% 12/27 spp  ETA 3.2 s" on stderr at most 4 times a second.
class ProgressBar {
public:
    ProgressBar(bool enabled, Clock::time_point start) : enabled_(enabled), start_(start) {
        if (enabled_) thread_ = std::thread([this] { loop(); });
    }
    ~ProgressBar() { finish(); }
    void update(double fraction, const std::string& label) {
        std::lock_guard<std::mutex> lock(m_);
        fraction_ = fraction;
        label_ = label;
    }
    void finish() {
        if (!thread_.joinable()) return;
        {
            std::lock_guard<std::mutex> lock(m_);
            done_ = true;
        }
        cv_.notify_all();
        thread_.join();
        print();
        std::fprintf(stderr, "\n");
    }

private:
    void loop() {
        std::unique_lock<std::mutex> lock(m_);
        while (!done_) {
            cv_.wait_for(lock, std::chrono::milliseconds(250));
            if (done_) break;
            lock.unlock();
            print();
            lock.lock();
        }
    }
    void print() {
        double f;
        std::string label;
        {
            std::lock_guard<std::mutex> lock(m_);
            f = std::clamp(fraction_, 0.0, 1.0);
            label = label_;
        }
        const double el = secondsSince(start_);
        const int width = 30, filled = int(f * width);
        std::string bar(filled, '=');
        if (filled < width) bar += '>' + std::string(width - filled - 1, ' ');
        const double eta = f > 1e-6 ? el * (1 - f) / f : 0.0;
        std::fprintf(stderr, "\r[%s] %3d%% %s  %.1f s elapsed, ETA %.1f s   ", bar.c_str(), int(f * 100), label.c_str(), el, eta);
        std::fflush(stderr);
    }

    bool enabled_;
    Clock::time_point start_;
    std::thread thread_;
    std::mutex m_;
    std::condition_variable cv_;
    bool done_ = false;
    double fraction_ = 0;
    std::string label_;
};
/// Polarized mode is spectral (not RGB) and needs an integrator with a polarized form; the
/// `stokes` integrator (Mitsuba 3: "should only be used in polarized mode") needs polarized mode.
void checkPolarizedMode(const Scene& scene, const RenderOptions& opt) {
    const IntegratorPtr& integrator = scene.description().integrator;
    if (opt.polarized && opt.rgbMode) fail("polarized mode is spectral: it cannot be combined with RGB mode");
    if (opt.polarized && integrator && !integrator->hasPolarizedForm())
        fail("polarized mode: the ", integrator->type(), " integrator has no polarized form (docs/polarization.md)");
    if (!opt.polarized && integrator && integrator->type() == "stokes")
        fail("the stokes integrator needs polarized mode (render --mode polarized)");
}

}  // namespace

Renderer::Renderer(const Scene& scene, const RenderOptions& options) : scene_(scene), opt_(options) {
    spp_ = opt_.spp >= 0 ? opt_.spp : scene.description().spp;
    if (spp_ < 0) fail("samples per pixel must be >= 0, got ", spp_);
    if (spp_ == 0 && !(opt_.timeLimit > 0)) fail("--spp 0 needs a --time-limit");
    if (!opt_.rgbMode && (opt_.spectralSamples < 1 || opt_.spectralSamples > kMaxWavelengths))
        fail("--spectral-samples must be in [1, ", kMaxWavelengths, "], got ", opt_.spectralSamples);
    for (int i = 0; i < 3; ++i)
        if (!(opt_.rgbWavelengths[i] >= kLambdaMin && opt_.rgbWavelengths[i] <= kLambdaMax))
            fail("RGB channel wavelengths must be in [", kLambdaMin, ", ", kLambdaMax, "] nm");
    checkPolarizedMode(scene, opt_);
    if (opt_.threads < 0) fail("--threads must be >= 0");
    if (opt_.firstSample < 0) fail("the first sample index must be >= 0, got ", opt_.firstSample);
    if (opt_.firstSample > 0 && spp_ == 0) fail("a sample range needs a fixed sample count, not --spp 0");
    if (int64_t(opt_.firstSample) + spp_ > int64_t(INT32_MAX)) fail("sample range end exceeds 2^31 - 1");
    pattern_ = scene.description().samplePattern;
    if (!opt_.sampler.empty()) pattern_.sequence = sampleSequenceNamed(opt_.sampler);
    if (opt_.patternSize < 0) fail("the sampler's pattern size must be >= 0, got ", opt_.patternSize);
    pattern_.size = uint32_t(std::max(1, opt_.patternSize > 0 ? opt_.patternSize : scene.description().spp));
}

std::string Renderer::settingsKey() const {
    const CameraDescription& c = scene_.description().camera;
    const IntegratorPtr& integrator = scene_.description().integrator;
    return strCat("scene=", scene_.description().sourceFile, ";mode=", opt_.rgbMode ? "rgb" : opt_.polarized ? "polarized" : "spectral",
                  ";n=", opt_.rgbMode ? 3 : opt_.spectralSamples, ";rgbl=", opt_.rgbWavelengths.x, ",",
                  opt_.rgbWavelengths.y, ",", opt_.rgbWavelengths.z, ";uniform=", opt_.uniformWavelengths,
                  opt_.independentWavelengths ? ";wavelengths=independent" : "",
                  ";seed=", opt_.seed, ";res=", c.width, "x", c.height, ";integrator=", integrator ? integrator->type() : kDefaultIntegrator,
                  ";maxdepth=", integrator ? integrator->maxDepth() : -1, ";scene_hash=", opt_.sceneHash,
                  ";first_sample=", opt_.firstSample, samplerKey());
}

std::string Renderer::samplerName() const {
    const SampleSequence q = pattern_.sequence;
    const bool patterned = q == SampleSequence::Stratified || q == SampleSequence::Multijitter;
    return strCat(sampleSequenceName(q), patterned ? strCat("/", pattern_.size) : std::string(), patterned && !pattern_.jitter ? "/nojitter" : "");
}

std::string Renderer::samplerKey() const {
    // Absent for the independent sampler, so checkpoints of earlier versions stay compatible.
    return pattern_.sequence == SampleSequence::Independent ? std::string() : ";sampler=" + samplerName();
}

std::string Renderer::stateHeader() const {
    return strCat(settingsKey(), "\nsamples=", opt_.firstSample, ":",
                  spp_ > 0 ? std::to_string(opt_.firstSample + spp_) : std::string());
}

RenderStats Renderer::render(Film& film, const std::atomic<bool>* cancel, SpectralFilm* spectral, StokesFilm* stokes) const {
    const auto start = Clock::now();
    const CameraDescription& camera = scene_.description().camera;
    if (!camera.sensor) fail("the scene has no sensor");
    if (film.width() != camera.width || film.height() != camera.height) fail("film and camera sizes differ");
    const ReconstructionFilterPtr filter = camera.filter ? camera.filter : makeFilter(kDefaultFilter);
    const IntegratorPtr integrator = scene_.description().integrator ? scene_.description().integrator : makeIntegrator(kDefaultIntegrator);
    if (spectral && opt_.rgbMode) fail("a spectral image needs spectral mode (RGB-mode channels are not wavelength samples)");
    if (spectral && integrator->splats()) fail("a spectral image (--spectral-output) is not available with the '", integrator->type(), "' integrator");
    // Light tracing: the splats of each pass, added to the film when the pass is complete.
    std::optional<SplatFilm> splats;
    if (integrator->splats()) splats.emplace(film.width(), film.height(), *filter, opt_.rgbMode);
    if (spectral && (spectral->width() != film.width() || spectral->height() != film.height() || film.totalSamples() > 0))
        fail("the spectral film must have the film's size and start empty");
    if (stokes && (!opt_.polarized || stokes->width() != film.width() || stokes->height() != film.height()))
        fail("a Stokes film needs polarized mode and the film's size");

    std::unique_ptr<tbb::global_control> limit;
    if (opt_.threads > 0) limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, opt_.threads);

    const int w = film.width(), h = film.height();
    const int tilesX = (w + kTile - 1) / kTile, tilesY = (h + kTile - 1) / kTile;
    const int nTiles = tilesX * tilesY;

    struct ThreadState {
        Arena arena;
        PathStats stats;
        uint64_t invalid = 0;
        int worker = -1;                  // the timeline's worker number
        std::vector<TileTiming> timings;  // this worker's tiles (RenderOptions::timeline)
    };
    std::atomic<int> workers{0};
    tbb::enumerable_thread_specific<ThreadState> states;

    // Resume: the film already holds complete passes (checkpoints are written between passes).
    const uint32_t firstSample = film.minSampleCount();
    if (film.totalSamples() != uint64_t(firstSample) * uint64_t(w) * uint64_t(h))
        fail("cannot resume: the film holds an incomplete pass");

    ProgressBar progress(opt_.progress, start);
    std::atomic<int> tilesDone{0};
    std::atomic<uint64_t> tilesFinished{0};
    RenderStats rs;
    auto lastCheckpoint = Clock::now();
    const bool unlimitedSpp = spp_ == 0;
    const int target = unlimitedSpp ? std::numeric_limits<int>::max() : spp_;
    double passSeconds = 0;

    auto stopRequested = [&] {
        if (cancel && cancel->load(std::memory_order_relaxed)) return true;
        return opt_.timeLimit > 0 && secondsSince(start) >= opt_.timeLimit;
    };

    // With checkpoints enabled, keep the last complete pass so that an interrupted render can
    // still be resumed exactly.
    const bool checkpoints = !opt_.checkpointPath.empty();
    std::optional<Film> lastComplete;
    if (checkpoints) lastComplete = film;

    for (int s = int(firstSample); s < target; ++s) {
        // Do not start a pass that cannot finish within the time limit.
        if (opt_.timeLimit > 0 && s > int(firstSample) && secondsSince(start) + passSeconds > opt_.timeLimit) {
            rs.timeLimited = true;
            break;
        }
        if (stopRequested()) break;
        const auto passStart = Clock::now();
        if (opt_.timeline) opt_.timeline->passes.push_back({secondsSince(start), 0.0});
        tilesDone = 0;
        ForkJoin forkJoin;  // the loop's order, for ThreadSanitizer (core/tsan_fork_join.h)
        forkJoin.fork();
        tbb::parallel_for(tbb::blocked_range<int>(0, nTiles, 1), [&](const tbb::blocked_range<int>& range) {
            const ForkJoin::Body body(forkJoin);
            ThreadState& ts = states.local();
            if (opt_.timeline && ts.worker < 0) ts.worker = workers++;
            for (int tile = range.begin(); tile != range.end(); ++tile) {
                if (stopRequested()) return;
                const double tileStart = opt_.timeline ? secondsSince(start) : 0.0;
                const int x0 = (tile % tilesX) * kTile, y0 = (tile / tilesX) * kTile;
                for (int y = y0; y < std::min(y0 + kTile, h); ++y)
                    for (int x = x0; x < std::min(x0 + kTile, w); ++x) {
                        const uint64_t pixelIndex = uint64_t(y) * w + x;
                        Sampler sampler(opt_.seed, pixelIndex, uint64_t(opt_.firstSample) + uint64_t(s), pattern_);
                        SampledWavelengths wl = opt_.rgbMode ? SampledWavelengths::rgb(opt_.rgbWavelengths)
                                                : opt_.independentWavelengths ? independentWavelengths(sampler, opt_)
                                                : opt_.uniformWavelengths
                                                    ? SampledWavelengths::sampleUniform(sampler.get1D(), opt_.spectralSamples)
                                                    : SampledWavelengths::sampleVisible(sampler.get1D(), opt_.spectralSamples);
                        const FilterSample fs = filter->sample(sampler.get2D());
                        const Ray ray = camera.sensor->generateRay(vec2(x + 0.5f, y + 0.5f) + fs.offset);
                        ts.arena.reset();
                        StokesVector S;
                        SampledSpectrum L = splats ? integrator->sample(scene_, ray, wl, sampler, ts.arena, ts.stats, *splats)
                                          : opt_.polarized ? polarizedSample(*integrator, scene_, ray, wl, sampler, ts.arena, ts.stats, &S)
                                                           : integrator->Li(scene_, ray, wl, sampler, ts.arena, ts.stats);
                        vec3 value;
                        if (opt_.rgbMode)
                            value = vec3(L[0], L[1], L[2]);
                        else
                            value = toXYZ(L, wl);
                        const bool valid = isFinite(value) && !L.hasNegative() && (!opt_.polarized || validStokes(S));
                        if (!valid) {
                            ++ts.invalid;
                            value = vec3(0.0f);
                        }
                        if (splats) {
                            splats->add(x, y, fs.weight * value);
                            continue;
                        }
                        film.addSample(x, y, fs.weight == 1.0f ? value : fs.weight * value);
                        if (spectral) valid ? spectral->addSample(x, y, fs.weight == 1.0f ? L : fs.weight * L, wl) : spectral->addZeroSample(x, y);
                        if (stokes) stokes->addSample(x, y, S, wl, fs.weight, valid);
                    }
                if (opt_.timeline) ts.timings.push_back({s - int(firstSample), tile, ts.worker, tileStart, secondsSince(start)});
                const int done = ++tilesDone;
                if (opt_.onTileFinished) opt_.onTileFinished(++tilesFinished, nTiles);
                if (opt_.progress || opt_.progressOut) {
                    const double frac = unlimitedSpp ? secondsSince(start) / opt_.timeLimit
                                                     : (double(s - firstSample) + double(done) / nTiles) / double(target - firstSample);
                    if (opt_.progressOut) opt_.progressOut->store(frac, std::memory_order_relaxed);
                    if (opt_.progress)
                        progress.update(frac, strCat(s + 1, "/", unlimitedSpp ? std::string("?") : std::to_string(target), " spp"));
                }
            }
        });
        forkJoin.join();
        passSeconds = std::chrono::duration<double>(Clock::now() - passStart).count();
        if (opt_.timeline) opt_.timeline->passes.back().end = secondsSince(start);
        if (tilesDone.load() < nTiles) break;  // stopped mid-pass (a splatting pass is dropped)
        if (splats) splats->flushInto(film);
        if (checkpoints) {
            lastComplete = film;
            if (opt_.checkpointEvery > 0 && secondsSince(lastCheckpoint) >= opt_.checkpointEvery) {
                // A failed periodic write (a full disk, a removed folder) must not stop the render
                // that it is meant to protect: it is retried at the next interval.
                try {
                    film.save(opt_.checkpointPath, stateHeader());
                    rs.checkpointError.clear();
                } catch (const Error& e) {
                    rs.checkpointError = e.what();
                }
                lastCheckpoint = Clock::now();
            }
        }
    }
    progress.finish();
    if (checkpoints) {  // the final state: rescued to a fallback path if its own write fails
        try {
            writeWithFallback(opt_.checkpointPath, [&](const std::string& path) { lastComplete->save(path, stateHeader()); });
            rs.checkpointError.clear();
        } catch (const Error& e) {
            rs.checkpointError = e.what();
        }
    }

    for (const ThreadState& ts : states) {
        rs.rays += ts.stats.rays;
        rs.paths += ts.stats.paths;
        rs.invalidSamples += ts.invalid;
        if (opt_.timeline) opt_.timeline->tiles.insert(opt_.timeline->tiles.end(), ts.timings.begin(), ts.timings.end());
    }
    if (splats) rs.invalidSamples += splats->invalidSplats();
    rs.seconds = secondsSince(start);
    rs.sppMin = film.minSampleCount();
    rs.sppMax = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) rs.sppMax = std::max(rs.sppMax, film.sampleCount(x, y));
    rs.interrupted = !unlimitedSpp && rs.sppMin < uint32_t(target) && !rs.timeLimited;
    if (opt_.timeLimit > 0 && secondsSince(start) >= opt_.timeLimit) rs.timeLimited = true;
    if (rs.timeLimited && (!cancel || !cancel->load())) rs.interrupted = false;
    if (opt_.timeline) opt_.timeline->end = secondsSince(start);
    return rs;
}

}  // namespace iris
