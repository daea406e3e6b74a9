// Performance targets 5 and 6 (docs/performance.md): the rough-plastic transmittance tables
// (materials/rough_plastic_tables.h) built at the default resolution on at most 2 threads, read back
// from a disk-cache file, and laziness: rendering scenes given with --lazy-scene=FILE[|name=value...]
// (1 spp, 32×32, the name=value pairs override the scene's <default>s)
// must acquire no rough-plastic table and build no RGB→spectrum grid unless the scene uses them.
// The laziness result is printed as one line per scene on stdout:
//   lazy <scene> tables_beckmann=<n> tables_ggx=<n> rgb_grid_built=<0|1>
// (the tables counters are process-wide, so later scenes see the acquisitions of earlier ones;
// list the scenes without rough plastic first). Benchmarks follow (use --benchmark_out for JSON).
//   build/bench_perf_tables [--lazy-scene=a.xml ...] [--benchmark_out=f.json]
#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <sys/resource.h>
#include <unistd.h>

#include "render/film.h"
#include "render/loader/scene_loader.h"
#include "render/renderer.h"
#include "render/scene.h"
#include "materials/rough_plastic_tables.h"
#include "spectral/rgb_spectrum_grid.h"

using namespace iris;

namespace {

std::string tablePath() {
    return (std::filesystem::temp_directory_path() / ("iris_perf_tables_" + std::to_string(::getpid()) + ".bin")).string();
}

double processCpuSeconds() {
    rusage ru{};
    getrusage(RUSAGE_SELF, &ru);
    return double(ru.ru_utime.tv_sec + ru.ru_stime.tv_sec) + 1e-6 * double(ru.ru_utime.tv_usec + ru.ru_stime.tv_usec);
}

/// Fresh build at the default resolution, TBB limited to 2 threads (the target's "2 cores").
void BM_TablesBuild2Threads(benchmark::State& state) {
    const auto type = state.range(0) == 0 ? MicrofacetType::Beckmann : MicrofacetType::GGX;
    state.SetLabel(state.range(0) == 0 ? "beckmann" : "ggx");
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
    const double cpu0 = processCpuSeconds();
    for (auto _ : state) benchmark::DoNotOptimize(buildRoughTables(type, RoughTableResolution{}));
    // CPU seconds of all threads: on a loaded machine, cpu/2 is what 2 free cores would take.
    state.counters["process_cpu_s"] = processCpuSeconds() - cpu0;
}
BENCHMARK(BM_TablesBuild2Threads)->DenseRange(0, 1)->Unit(benchmark::kMillisecond)->Iterations(1)->UseRealTime();

/// Read (and validate) the table file written by writeRoughTables.
void BM_TablesLoadFromDisk(benchmark::State& state) {
    const std::string path = tablePath();
    {
        const RoughTransmittanceTables t = buildRoughTables(MicrofacetType::Beckmann, RoughTableResolution{});
        if (!writeRoughTables(path, t)) {
            state.SkipWithError("cannot write the table file");
            return;
        }
    }
    state.counters["bytes"] = double(std::filesystem::file_size(path));
    for (auto _ : state) {
        std::string why;
        auto t = readRoughTables(path, MicrofacetType::Beckmann, RoughTableResolution{}, &why);
        if (!t) {
            state.SkipWithError(("read failed: " + why).c_str());
            break;
        }
        benchmark::DoNotOptimize(t->ext.data());
    }
    std::filesystem::remove(path);
}
BENCHMARK(BM_TablesLoadFromDisk)->Unit(benchmark::kMillisecond)->UseRealTime();

void checkLaziness(const std::string& arg) {
    // FILE|name=value|name=value
    std::vector<std::string> parts;
    for (size_t b = 0, e; b <= arg.size(); b = e + 1) {
        e = arg.find('|', b);
        if (e == std::string::npos) e = arg.size();
        parts.push_back(arg.substr(b, e - b));
    }
    const std::string path = parts[0];
    std::map<std::string, std::string> defines{{"res", "32"}};
    for (size_t i = 1; i < parts.size(); ++i) {
        const size_t eq = parts[i].find('=');
        if (eq != std::string::npos) defines[parts[i].substr(0, eq)] = parts[i].substr(eq + 1);
    }
    SceneDescription d = loadScene(path, defines);
    Scene scene(std::move(d));
    RenderOptions opt;
    opt.spp = 1;
    opt.threads = 1;
    Film film(scene.description().camera.width, scene.description().camera.height);
    Renderer(scene, opt).render(film);
    std::printf("lazy %s tables_beckmann=%d tables_ggx=%d rgb_grid_built=%d\n", arg.c_str(),
                roughPlasticTablesAcquired(MicrofacetType::Beckmann), roughPlasticTablesAcquired(MicrofacetType::GGX),
                int(RGBSpectrumGrid::built()));
    std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
    std::vector<char*> rest;
    for (int i = 0; i < argc; ++i) {
        if (std::strncmp(argv[i], "--lazy-scene=", 13) == 0) {
            try {
                checkLaziness(argv[i] + 13);
            } catch (const std::exception& e) {
                std::printf("lazy %s error: %s\n", argv[i] + 13, e.what());
            }
        } else {
            rest.push_back(argv[i]);
        }
    }
    int n = int(rest.size());
    benchmark::Initialize(&n, rest.data());
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
