// The render loop: progressive passes of one sample per pixel over 16×16 tiles in parallel (TBB).
// Each sample's random stream depends only on (seed, pixel, sample index) and every pixel is
// accumulated by one thread in sample order, so images are bit-identical for any thread count,
// and a resumed render equals an uninterrupted one. Cancellation (Ctrl-C) and the time limit stop
// between tiles; whatever was rendered is kept.
#pragma once

#include <atomic>
#include <functional>
#include <string>

#include "render/film.h"
#include "render/render_timeline.h"
#include "render/spectral_film.h"
#include "render/scene.h"

namespace iris {

class StokesFilm;  // render/stokes_film.h

struct RenderOptions {
    int spp = -1;                  // samples per pixel (-1: the scene's)
    int firstSample = 0;           // index of the first sample (a shard renders [firstSample, firstSample + spp))
    std::string sampler;           // sequence by sampler name ("" = the scene's; render/samplers/)
    int patternSize = 0;           // stratified/multijitter pattern size n (0 = the scene's sample_count);
                                   // the shards of one render must share it
    std::string sceneHash;         // identifies the scene file's content and -D overrides (render/scene_hash.h)
    double timeLimit = 0;          // seconds (0 = none); with spp = 0 render until the time is up
    uint64_t seed = 0;
    int threads = 0;               // 0 = all cores
    bool rgbMode = false;          // RGB mode: 3 fixed wavelengths, values are linear Rec.709
    bool polarized = false;        // polarized spectral mode: Stokes vectors per lane (docs/polarization.md)
    int spectralSamples = 4;       // N wavelengths per path in spectral mode
    vec3 rgbWavelengths = defaultChannelWavelengths();
    bool uniformWavelengths = false;  // ablation: uniform instead of visible-importance wavelength pdf
    bool independentWavelengths = false;  // ablation: N independent wavelengths instead of hero rotations
    bool progress = false;         // progress bar with ETA on stderr
    std::atomic<double>* progressOut = nullptr;  // if set, the fraction done (0..1) is stored here
                                                 // as tiles finish (the Python module's callback)
    std::string checkpointPath;    // "" = no checkpoints
    double checkpointEvery = 0;    // seconds between checkpoints (0 = only at the end/interrupt)
    bool resume = false;           // continue from checkpointPath
    // Called after every finished tile, on the worker thread that rendered it, with the number of
    // tiles finished in this render() call and the tiles per pass (a pass is finished when the
    // count reaches a multiple of it). Interruption tests use it to stop at an exact point.
    std::function<void(uint64_t tilesFinished, int tilesPerPass)> onTileFinished;
    // If set, filled with when each pass and tile ran (render/render_timeline.h; the scaling model).
    RenderTimeline* timeline = nullptr;
};

struct RenderStats {
    double seconds = 0;
    uint64_t rays = 0;
    uint64_t paths = 0;
    uint64_t invalidSamples = 0;   // NaN/Inf/negative estimates replaced by zero
    uint32_t sppMin = 0, sppMax = 0;
    bool interrupted = false;      // stopped by cancellation before reaching spp
    bool timeLimited = false;
    /// Why the checkpoint is not where it was asked, if it is not: a periodic write that failed is
    /// retried at the next interval and the render goes on; the final one goes to a fallback path,
    /// which this names (core/io/output_file.h). Empty when the last write succeeded.
    std::string checkpointError;
};

class Renderer {
public:
    Renderer(const Scene& scene, const RenderOptions& options);
    /// Render into `film`; `cancel` may be set asynchronously (signal handler) to stop early.
    /// `spectral`, if given (spectral mode only), receives the same samples binned by wavelength;
    /// `stokes` (polarized mode with the `stokes` integrator) the four Stokes components.
    RenderStats render(Film& film, const std::atomic<bool>* cancel = nullptr, SpectralFilm* spectral = nullptr,
                       StokesFilm* stokes = nullptr) const;
    /// String identifying everything that determines the image (checkpoint compatibility).
    std::string settingsKey() const;
    /// settingsKey() and a second line "samples=A:B" (the sample range this render is meant to hold;
    /// "A:" when the time limit decides): the header of checkpoints and film states.
    std::string stateHeader() const;
    int targetSpp() const { return spp_; }
    /// The sampler's sequence and, for stratified and multijitter, its pattern size: "sobol",
    /// "stratified/16", "multijitter/64/nojitter" (metadata iris.sampler).
    std::string samplerName() const;

private:
    std::string samplerKey() const;  // the sampler part of settingsKey()

    const Scene& scene_;
    RenderOptions opt_;
    int spp_;
    SamplePattern pattern_;
};

/// Convert a film to the image stored on disk: XYZ (spectral) or linear Rec.709 (RGB mode) in the
/// film's values; the caller converts colour spaces through OpenColorIO.
}  // namespace iris
