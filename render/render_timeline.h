// When the render loop did what, and a model of the loop on more cores built from it
// (experiments/benchmarks/bench_scaling_model.cpp, docs/performance.md "Scaling"). The timeline
// holds each tile's pass, worker and start and end, each pass's start and end, in seconds since
// Renderer::render began; it is recorded only when RenderOptions::timeline is set (two clock reads
// per tile) and is never part of an image.
#pragma once

#include <vector>

namespace iris {

struct TileTiming {
    int pass = 0;     // sample index of the pass (0 for the render's first)
    int tile = 0;     // index in the pass's row-major tile order
    int worker = 0;   // 0, 1, ...: the threads in the order they first took a tile
    double start = 0, end = 0;
};

struct PassTiming {
    double start = 0, end = 0;  // from before the pass's tiles are handed out until all are done
};

struct RenderTimeline {
    std::vector<PassTiming> passes;
    std::vector<TileTiming> tiles;  // grouped by worker, in the order each worker ran them
    double end = 0;                 // when render() returned its statistics
};

/// A timeline summed up: the render time, the time in tiles (`work`, summed over workers), the
/// time outside passes, and the worker time inside passes not in a tile (`idle`: waiting at the
/// pass's end, the loop's bookkeeping); per pass, its tiles' durations in tile order and its
/// `overhead`, the pass's span beyond its tile time ÷ `threads`.
struct PassWork {
    std::vector<double> tiles;
    double overhead = 0;
};
struct TimelineSummary {
    double total = 0, work = 0, outside = 0, idle = 0;
    std::vector<PassWork> passes;
};
TimelineSummary summarize(const RenderTimeline& timeline, int threads);

/// The loop's schedule of these passes on P workers (render/renderer.cpp): each pass hands its
/// tiles out in order to whichever worker is free first (list scheduling), and the next pass starts
/// when all are done; each pass's overhead is added as serial time. Returns the time the passes take.
double scheduleWithBarrier(const std::vector<PassWork>& passes, int P);

/// The same tiles without the barrier: in pass-major order to the first free worker, each starting
/// no earlier than its own tile's previous pass ended (so a pixel's samples stay in order); the
/// per-pass overheads are added as serial time.
double scheduleWithoutBarrier(const std::vector<PassWork>& passes, int P);

}  // namespace iris
