// Timings of the per-wavelength lane loops (docs/performance.md, target 2): wavelength sampling,
// RGB → spectrum evaluation (reflectance and illuminant) and the film's XYZ estimator, at
// N = 4, 16, 32 wavelengths, in the AVX2 build (where the CPU has it) and in the baseline build
// (spectral/lane_dispatch.h). Compare the CPU column.
#include <benchmark/benchmark.h>

#include "core/rng.h"
#include "spectral/lane_dispatch.h"
#include "spectral/rgb_spectrum.h"
#include "spectral/spectrum_factory.h"
#include "spectral/xyz.h"

using namespace iris;

namespace {
// state.range(0) = N, state.range(1) = 1 for the baseline build.
struct BuildChoice {
    explicit BuildChoice(const benchmark::State& state) { lanes::forceBaseline = state.range(1) != 0; }
    ~BuildChoice() { lanes::forceBaseline = false; }
};
void lanesArgs(benchmark::internal::Benchmark* b) {
    for (int n : {4, 16, 32})
        for (int baseline : {0, 1}) b->Args({n, baseline});
    b->ArgNames({"N", "baseline"});
}
}  // namespace

static void BM_SampleVisible(benchmark::State& state) {
    const BuildChoice build(state);
    const int n = int(state.range(0));
    float u = 0.1f;
    for (auto _ : state) {
        u = u + 0.618034f;
        if (u >= 1) u -= 1;
        benchmark::DoNotOptimize(SampledWavelengths::sampleVisible(u, n));
    }
}
BENCHMARK(BM_SampleVisible)->Apply(lanesArgs);

static void sampleSpectrum(benchmark::State& state, const SpectrumPtr& s) {
    const BuildChoice build(state);
    const SampledWavelengths wl = SampledWavelengths::sampleVisible(0.37f, int(state.range(0)));
    for (auto _ : state) benchmark::DoNotOptimize(s->sample(wl));
}
static void BM_RgbReflectanceSample(benchmark::State& state) {
    sampleSpectrum(state, makeRGBSpectrum(vec3(0.6f, 0.08f, 0.05f), SpectrumKind::Reflectance));
}
BENCHMARK(BM_RgbReflectanceSample)->Apply(lanesArgs);
static void BM_RgbIlluminantSample(benchmark::State& state) {
    sampleSpectrum(state, makeRGBSpectrum(vec3(0.35f, 0.38f, 0.45f), SpectrumKind::Illuminant));
}
BENCHMARK(BM_RgbIlluminantSample)->Apply(lanesArgs);

static void BM_ToXYZLanes(benchmark::State& state) {
    const BuildChoice build(state);
    const int n = int(state.range(0));
    const SampledWavelengths wl = SampledWavelengths::sampleVisible(0.3f, n);
    SampledSpectrum L(n);
    Pcg32 rng(1, 1);
    for (int i = 0; i < n; ++i) L[i] = rng.uniform();
    for (auto _ : state) benchmark::DoNotOptimize(toXYZ(L, wl));
}
BENCHMARK(BM_ToXYZLanes)->Apply(lanesArgs);

BENCHMARK_MAIN();
