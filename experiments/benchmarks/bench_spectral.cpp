// Timings of the spectral module: the per-colour Jakob–Hanika sigmoid fit (paid once per distinct
// RGB value at scene construction), spectrum evaluation, and the film's XYZ estimator.
#include <benchmark/benchmark.h>

#include "core/rng.h"
#include "spectral/rgb_spectrum.h"
#include "spectral/rgb_spectrum_grid.h"
#include "spectral/spectrum_factory.h"
#include "spectral/xyz.h"

using namespace iris;

static void BM_RgbReflectanceFit(benchmark::State& state) {
    Pcg32 rng(1, 2);
    for (auto _ : state) {
        const vec3 rgb(0.02f + 0.96f * rng.uniform(), 0.02f + 0.96f * rng.uniform(), 0.02f + 0.96f * rng.uniform());
        benchmark::DoNotOptimize(makeRGBSpectrum(rgb, SpectrumKind::Reflectance));
    }
}
BENCHMARK(BM_RgbReflectanceFit)->Unit(benchmark::kMicrosecond);

static void BM_RgbSpectrumSample(benchmark::State& state) {
    const SpectrumPtr s = makeRGBSpectrum(vec3(0.7f, 0.3f, 0.1f), SpectrumKind::Reflectance);
    const int n = int(state.range(0));
    float u = 0.1f;
    for (auto _ : state) {
        u = u + 0.618034f;
        if (u >= 1) u -= 1;
        benchmark::DoNotOptimize(s->sample(SampledWavelengths::sampleVisible(u, n)));
    }
}
BENCHMARK(BM_RgbSpectrumSample)->Arg(4)->Arg(8)->Arg(16);

static void BM_ToXYZ(benchmark::State& state) {
    const int n = int(state.range(0));
    const SampledWavelengths wl = SampledWavelengths::sampleVisible(0.3f, n);
    const SampledSpectrum L(n, 0.5f);
    for (auto _ : state) benchmark::DoNotOptimize(toXYZ(L, wl));
}
BENCHMARK(BM_ToXYZ)->Arg(4)->Arg(8)->Arg(16);

static void BM_GridReflectanceSample(benchmark::State& state) {
    const RGBSpectrumGrid& grid = RGBSpectrumGrid::instance();  // built outside the timed loop
    const int n = int(state.range(0));
    const SampledWavelengths wl = SampledWavelengths::sampleVisible(0.3f, n);
    Pcg32 rng(3, 4);
    for (auto _ : state) {
        const vec3 rgb(rng.uniform(), rng.uniform(), rng.uniform());
        benchmark::DoNotOptimize(grid.reflectance(rgb, wl));
    }
}
BENCHMARK(BM_GridReflectanceSample)->Arg(4)->Arg(8)->Arg(16);

BENCHMARK_MAIN();
