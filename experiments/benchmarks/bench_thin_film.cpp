// Cost of the thin-film optics (spectral/thin_film_stack.h) and of the thin-film BSDFs:
// Airy closed form vs transfer matrix vs truncated / incoherent sums, the Belcour–Barla RGB
// integration, and eval() of thinfilm / iridescent_diffuse at 4 wavelengths.
//   build/bench_thin_film [--benchmark_filter=...]
#include <benchmark/benchmark.h>

#include <vector>

#include "core/arena.h"
#include "core/registry.h"
#include "spectral/belcour_barla.h"
#include "materials/material.h"
#include "spectral/thin_film_stack.h"

using namespace iris;

namespace {

const Layer kFilm{complexd(1.45, 0.0), 420.0};
const complexd kMetal(0.2, 3.2);

void BM_AirySingleFilm(benchmark::State& st) {
    double c = 0.3;
    for (auto _ : st) {
        benchmark::DoNotOptimize(airySingleFilm(550.0, c, 1.0, kFilm, kMetal));
        c = c < 0.99 ? c + 1e-3 : 0.3;
    }
}
BENCHMARK(BM_AirySingleFilm);

void BM_TransferMatrix(benchmark::State& st) {
    std::vector<Layer> layers(st.range(0), kFilm);
    double c = 0.3;
    for (auto _ : st) {
        benchmark::DoNotOptimize(thinFilmStackRT(550.0, c, 1.0, layers, kMetal));
        c = c < 0.99 ? c + 1e-3 : 0.3;
    }
}
BENCHMARK(BM_TransferMatrix)->Arg(1)->Arg(3)->Arg(10)->Arg(50);

void BM_Truncated(benchmark::State& st) {
    double c = 0.3;
    for (auto _ : st) {
        benchmark::DoNotOptimize(truncatedSingleFilm(550.0, c, 1.0, kFilm, kMetal, int(st.range(0))));
        c = c < 0.99 ? c + 1e-3 : 0.3;
    }
}
BENCHMARK(BM_Truncated)->Arg(1)->Arg(8);

void BM_Incoherent(benchmark::State& st) {
    double c = 0.3;
    for (auto _ : st) {
        benchmark::DoNotOptimize(incoherentSingleFilm(550.0, c, 1.0, kFilm, kMetal));
        c = c < 0.99 ? c + 1e-3 : 0.3;
    }
}
BENCHMARK(BM_Incoherent);

void BM_BelcourBarlaRGB(benchmark::State& st) {
    double c = 0.3;
    for (auto _ : st) {
        for (int ch = 0; ch < 3; ++ch) benchmark::DoNotOptimize(belcourBarlaReflectance(ch, c, 1.0, 1.45, 420.0, kMetal));
        c = c < 0.99 ? c + 1e-3 : 0.3;
    }
}
BENCHMARK(BM_BelcourBarlaRGB);

/// getBSDF + one eval of a registered material at 4 spectral wavelengths.
void benchMaterial(benchmark::State& st, const char* type, bool rough) {
    Properties p("bsdf", type, {});
    p.set("thickness", 420.0f, {});
    if (rough) p.set("alpha", 0.2f, {});
    const auto mat = MaterialRegistry::instance().create(p);
    Arena arena;
    ShadingPoint sp;
    const vec3 wo = glm::normalize(vec3(0.3f, 0.1f, 0.9f)), wi = glm::normalize(vec3(-0.2f, 0.3f, 0.8f));
    float u = 0.1f;
    for (auto _ : st) {
        SampledWavelengths wl = SampledWavelengths::sampleVisible(u, 4);
        const BSDF* b = mat->getBSDF(sp, wl, arena);
        benchmark::DoNotOptimize(b->eval(wo, wi, TransportMode::Radiance));
        arena.reset();
        u = u < 0.9f ? u + 0.013f : 0.1f;
    }
}
void BM_ThinFilmRoughEval(benchmark::State& st) { benchMaterial(st, "thinfilm", true); }
void BM_IridescentDiffuseRoughEval(benchmark::State& st) { benchMaterial(st, "iridescent_diffuse", true); }
BENCHMARK(BM_ThinFilmRoughEval);
BENCHMARK(BM_IridescentDiffuseRoughEval);

}  // namespace

BENCHMARK_MAIN();
