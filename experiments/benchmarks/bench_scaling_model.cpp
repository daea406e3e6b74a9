// A measured model of how the render loop scales with cores (issue 37, item 3; docs/performance.md,
// "Scaling"). Renders a scene with 1 thread and with T threads (T = this machine's cores), each
// with the loop's timeline (render/render_timeline.h: every tile's start and end), and reports:
//   1. where the T-thread run loses time against T1 / T, measured: tiles that run slower when the
//      other cores work too (shared caches, memory bandwidth, the hypervisor: "contention"), cores
//      idle at the end of each pass (the barrier: "pass ends"), and work outside the passes
//      (set-up, checkpoints: "serial");
//   2. the loop's own limit on P cores: the 1-thread tile times scheduled on P workers as the loop
//      hands them out (each free worker takes the next tile; a barrier after each pass), with the
//      measured per-pass and outside overheads kept serial. A second column schedules the same
//      tiles without the barrier (a tile's next pass may start once its previous one is done), the
//      design tried in a7cdc49 and reverted because 2 cores could not tell the difference.
// Contention above T cores cannot be measured here; the model leaves it out (an upper bound on
// the speed-up) and prints the contention measured at T beside it.
//
//   build/bench_scaling_model [--scene=scenes/default.xml] [-Dres=192] [--spp=64] [--reps=3]
//                             [--threads=T] [--out=FILE.md]
#include <algorithm>
#include <cstdio>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "core/io/atomic_file.h"
#include "core/source_tree.h"
#include "render/loader/scene_loader.h"
#include "render/renderer.h"
#include "render/scene.h"

using namespace iris;

namespace {

struct Args {
    std::string scene = sourcePath("scenes/default.xml");
    std::map<std::string, std::string> defines{{"res", "192"}};
    int spp = 64, reps = 3, threads = int(std::max(2u, std::thread::hardware_concurrency()));
    std::string out;
};

Args parse(int argc, char** argv) {
    Args a;
    for (int i = 1; i < argc; ++i) {
        const std::string s = argv[i];
        const auto value = [&](const std::string& key) { return s.rfind(key, 0) == 0 ? s.substr(key.size()) : std::string(); };
        if (!value("--scene=").empty()) a.scene = value("--scene=");
        else if (!value("--spp=").empty()) a.spp = std::stoi(value("--spp="));
        else if (!value("--reps=").empty()) a.reps = std::stoi(value("--reps="));
        else if (!value("--threads=").empty()) a.threads = std::stoi(value("--threads="));
        else if (!value("--out=").empty()) a.out = value("--out=");
        else if (!value("-D").empty() && s.find('=') != std::string::npos) {
            const std::string kv = value("-D");
            a.defines[kv.substr(0, kv.find('='))] = kv.substr(kv.find('=') + 1);
        } else {
            std::cerr << "bench_scaling_model: unknown argument '" << s << "'\n";
            std::exit(2);
        }
    }
    if (a.spp < 1 || a.reps < 1 || a.threads < 2) {
        std::cerr << "bench_scaling_model: --spp and --reps must be >= 1, --threads >= 2\n";
        std::exit(2);
    }
    return a;
}

RenderTimeline renderTimed(const Scene& scene, int spp, int threads) {
    RenderTimeline tl;
    RenderOptions opt;
    opt.spp = spp;
    opt.threads = threads;
    opt.seed = 1;
    opt.timeline = &tl;
    Film film(scene.description().camera.width, scene.description().camera.height);
    Renderer(scene, opt).render(film);
    return tl;
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

}  // namespace

int main(int argc, char** argv) {
    const Args a = parse(argc, argv);
    const Scene scene(loadScene(a.scene, a.defines));
    renderTimed(scene, 1, a.threads);  // warm-up: lazily built tables, the thread pool

    // Interleaved repetitions; the repetition whose speed-up is the median is the one analysed.
    std::vector<std::pair<TimelineSummary, TimelineSummary>> runs;
    std::vector<double> speedups;
    for (int r = 0; r < a.reps; ++r) {
        runs.emplace_back(summarize(renderTimed(scene, a.spp, 1), 1), summarize(renderTimed(scene, a.spp, a.threads), a.threads));
        speedups.push_back(runs.back().first.total / runs.back().second.total);
    }
    const double med = median(speedups);
    size_t pick = 0;
    for (size_t r = 0; r < runs.size(); ++r)
        if (std::abs(speedups[r] - med) < std::abs(speedups[pick] - med)) pick = r;
    const TimelineSummary& one = runs[pick].first;
    const TimelineSummary& many = runs[pick].second;
    const int T = a.threads;
    const size_t tilesPerPass = one.passes.empty() ? 0 : one.passes[0].tiles.size();

    std::ostringstream md;
    char buf[512];
    const auto line = [&](const char* fmt, auto... v) {
        std::snprintf(buf, sizeof buf, fmt, v...);
        md << buf << "\n";
    };
    std::string defs;
    for (const auto& [k, v] : a.defines) defs += " -D " + k + "=" + v;
    line("Scene `%s`%s, %d spp, %zu tiles of 16×16 per pass; %d repetitions of 1 and %d threads, interleaved "
         "(speed-ups per repetition:", a.scene.substr(a.scene.rfind("scenes/") == std::string::npos ? 0 : a.scene.rfind("scenes/")).c_str(),
         defs.c_str(), a.spp, tilesPerPass, a.reps, T);
    std::string per;
    for (double s : speedups) per += (per.empty() ? "" : ", ") + std::to_string(s).substr(0, 4);
    line("%s; the median one is analysed).", per.c_str());
    // T-thread time − T1 / T splits exactly into the three parts: T1 = outside₁ + work₁ + idle₁ (the
    // one thread's loop bookkeeping inside passes), and T_T = outside_T + (work_T + idle_T) / T.
    const double ideal = one.total / T;
    const double contention = (many.work - one.work) / T, passEnds = (many.idle - one.idle) / T,
                 serial = many.outside - one.outside / T;
    line("\n### Where %d threads lose time, measured\n", T);
    line("| part | seconds | share of the %d-thread time |", T);
    line("|---|---|---|");
    line("| T1 ÷ %d: the 1-thread render time (%.3f s) shared without loss | %.3f | %.1f %% |", T, one.total, ideal,
         100 * ideal / many.total);
    line("| contention: tile work at %d threads − at 1, ÷ %d (each tile %.1f %% slower) | %.3f | %.1f %% |", T, T,
         100 * (many.work / one.work - 1), contention, 100 * contention / many.total);
    line("| pass ends: worker time inside passes not in a tile (idle at the barrier, the loop's bookkeeping), "
         "beyond 1 thread's, ÷ %d | %.3f | %.1f %% |", T, passEnds, 100 * passEnds / many.total);
    line("| serial: outside the passes, beyond 1 thread's ÷ %d | %.3f | %.1f %% |", T, serial, 100 * serial / many.total);
    line("| measured %d-thread render time (the sum) | %.3f | 100 %% |", T, many.total);
    line("\nSpeed-up %.2f×, %.2f of %d.", one.total / many.total, one.total / many.total / T, T);

    line("\n### The loop's limit on P cores, modelled from the 1-thread tile times\n");
    line("No contention above %d cores is modelled (the figures are upper bounds); measured at %d: tiles %.1f %% slower.\n",
         T, T, 100 * (many.work / one.work - 1));
    line("| cores P | modelled speed-up, barrier per pass (the loop) | efficiency | without the barrier | efficiency |");
    line("|---|---|---|---|---|");
    for (int P : {1, 2, 4, 8, 16, 32, 64, 128}) {
        const double withB = one.outside + scheduleWithBarrier(one.passes, P);
        const double without = one.outside + scheduleWithoutBarrier(one.passes, P);
        line("| %d | %.2f× | %.2f | %.2f× | %.2f |", P, one.total / withB, one.total / withB / P, one.total / without,
             one.total / without / P);
    }
    // The check: the model at P = T, once as it is and once with every tile slowed by the measured
    // contention, against the measured speed-up.
    const double model = one.outside + scheduleWithBarrier(one.passes, T);
    const double slowed = one.outside + (model - one.outside) * many.work / one.work;
    line("\nCheck at P = %d: the model gives %.2f×, %.2f× with the tiles slowed by the measured contention; measured %.2f×.",
         T, one.total / model, one.total / slowed, one.total / many.total);

    if (a.out.empty()) {
        std::cout << md.str();
        return 0;
    }
    try {
        writeFileAtomically(a.out, md.str());  // never a half-written report
    } catch (const std::exception& e) {
        std::cerr << "bench_scaling_model: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
