// The render loop's timeline summed up, and its schedule on P workers (render/render_timeline.h).
#include "render/render_timeline.h"

#include <algorithm>
#include <functional>
#include <queue>

namespace iris {

namespace {

/// Workers as a min-heap of the times they become free.
using FreeWorkers = std::priority_queue<double, std::vector<double>, std::greater<double>>;

FreeWorkers idleWorkers(int P) {
    FreeWorkers free;
    for (int w = 0; w < P; ++w) free.push(0.0);
    return free;
}

}  // namespace

TimelineSummary summarize(const RenderTimeline& tl, int threads) {
    TimelineSummary b;
    b.total = tl.end;
    b.passes.resize(tl.passes.size());
    double inPasses = 0;
    for (const PassTiming& p : tl.passes) inPasses += p.end - p.start;
    for (const TileTiming& t : tl.tiles) {
        PassWork& pw = b.passes[size_t(t.pass)];
        if (pw.tiles.size() <= size_t(t.tile)) pw.tiles.resize(size_t(t.tile) + 1, 0.0);
        pw.tiles[size_t(t.tile)] = t.end - t.start;
        b.work += t.end - t.start;
    }
    for (size_t p = 0; p < b.passes.size(); ++p) {
        double sum = 0;
        for (double d : b.passes[p].tiles) sum += d;
        const double span = tl.passes[p].end - tl.passes[p].start;
        b.passes[p].overhead = std::max(0.0, span - sum / threads);
        b.idle += threads * span - sum;
    }
    b.outside = b.total - inPasses;
    return b;
}

double scheduleWithBarrier(const std::vector<PassWork>& passes, int P) {
    double t = 0;
    for (const PassWork& pw : passes) {
        FreeWorkers free = idleWorkers(P);
        double makespan = 0;
        for (double d : pw.tiles) {
            const double end = free.top() + d;
            free.pop();
            free.push(end);
            makespan = std::max(makespan, end);
        }
        t += makespan + pw.overhead;
    }
    return t;
}

double scheduleWithoutBarrier(const std::vector<PassWork>& passes, int P) {
    FreeWorkers free = idleWorkers(P);
    std::vector<double> previousEnd;  // per tile: when its previous pass ended
    double makespan = 0, overhead = 0;
    for (const PassWork& pw : passes) {
        previousEnd.resize(std::max(previousEnd.size(), pw.tiles.size()), 0.0);
        for (size_t i = 0; i < pw.tiles.size(); ++i) {
            const double end = std::max(free.top(), previousEnd[i]) + pw.tiles[i];
            free.pop();
            free.push(end);
            previousEnd[i] = end;
            makespan = std::max(makespan, end);
        }
        overhead += pw.overhead;
    }
    return makespan + overhead;
}

}  // namespace iris
