// Per-call cost of the thesis' models (thesis 000 Table 4.5 compares whole renders of Granier and
// the proposed model): eval and sample in RGB mode with the thesis' parameter sets, and the
// rough plastic table build (fresh, TBB).
#include <benchmark/benchmark.h>

#include "core/arena.h"
#include "core/registry.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "materials/material.h"
#include "materials/rough_plastic_tables.h"
#include "render/loader/scene_upgrade.h"

using namespace iris;

namespace {

struct Instance {
    std::shared_ptr<Material> material;
    Arena arena;
    const BSDF* bsdf = nullptr;
};

std::unique_ptr<Instance> make(const std::string& type, std::initializer_list<std::pair<std::string, PropertyValue>> params) {
    Properties p("bsdf", type, SourceLocation{"bench", 0});
    for (const auto& [k, v] : params) p.set(k, v, SourceLocation{"bench", 0});
    // The thesis' models as a version 0.x file's objects (Mitsuba 0.6's roughplastic;
    // docs/scene_format.md): the upgrade pass's rules.
    p.setFormatVersion(0);
    upgradeObject(p);
    auto inst = std::make_unique<Instance>();
    inst->material = MaterialRegistry::instance().create(p);
    SampledWavelengths wl = SampledWavelengths::rgb(defaultChannelWavelengths());
    inst->bsdf = inst->material->getBSDF(ShadingPoint{}, wl, inst->arena);
    return inst;
}

std::unique_ptr<Instance> byIndex(int64_t i) {
    const PropertyValue tilt10 = VectorValue{vec3(0.1736f, 0, 0.9848f)};
    const PropertyValue eta = RGBValue{vec3(1.5f, 1.6f, 1.8f)};
    switch (i) {
        case 0: return make("granier", {{"n0", tilt10}, {"eta_t", eta}});
        case 1: return make("proposed", {{"n0", tilt10}, {"eta_t", eta}, {"thickness", 76.0f}, {"alpha", 0.124f}});
        case 2:
            return make("proposed", {{"n0", tilt10}, {"eta_t", eta}, {"thickness", 76.0f}, {"alpha", 0.124f},
                                     {"phase_mode", std::string("per_reflection")}});
        default: return make("roughplastic", {{"alpha", 0.124f}});
    }
}
const char* kNames[] = {"granier", "proposed_total", "proposed_per_reflection", "roughplastic"};

void BM_Eval(benchmark::State& state) {
    auto inst = byIndex(state.range(0));
    state.SetLabel(kNames[state.range(0)]);
    Pcg32 rng(1, 2);
    for (auto _ : state) {
        const vec3 wo = sampleCosineHemisphere(vec2(rng.uniform(), rng.uniform()));
        const vec3 wi = sampleCosineHemisphere(vec2(rng.uniform(), rng.uniform()));
        benchmark::DoNotOptimize(inst->bsdf->eval(wo, wi, TransportMode::Radiance));
    }
}
BENCHMARK(BM_Eval)->DenseRange(0, 3);

void BM_Sample(benchmark::State& state) {
    auto inst = byIndex(state.range(0));
    state.SetLabel(kNames[state.range(0)]);
    Pcg32 rng(3, 4);
    for (auto _ : state) {
        const vec3 wo = sampleCosineHemisphere(vec2(rng.uniform(), rng.uniform()));
        benchmark::DoNotOptimize(
            inst->bsdf->sample(wo, rng.uniform(), vec2(rng.uniform(), rng.uniform()), TransportMode::Radiance));
    }
}
BENCHMARK(BM_Sample)->DenseRange(0, 3);

/// What the direct/path integrator does at one shading point (integrators/path.cpp): getBSDF, then
/// next-event estimation (eval + pdf towards a light direction), then one BSDF sample. Arg 1: 0 =
/// RGB mode, 4 = spectral with 4 wavelengths. Label: model, mode.
void BM_ShadingPoint(benchmark::State& state) {
    auto inst = byIndex(state.range(0));
    const int nSpectral = int(state.range(1));
    state.SetLabel(std::string(kNames[state.range(0)]) + (nSpectral ? " spectral" : " rgb"));
    Pcg32 rng(5, 6);
    Arena arena;
    for (auto _ : state) {
        SampledWavelengths wl = nSpectral ? SampledWavelengths::sampleVisible(rng.uniform(), nSpectral)
                                          : SampledWavelengths::rgb(defaultChannelWavelengths());
        const BSDF* bsdf = inst->material->getBSDF(ShadingPoint{}, wl, arena);
        const vec3 wo = sampleCosineHemisphere(vec2(rng.uniform(), rng.uniform()));
        const vec3 wl0 = sampleCosineHemisphere(vec2(rng.uniform(), rng.uniform()));
        benchmark::DoNotOptimize(bsdf->eval(wo, wl0, TransportMode::Radiance));
        benchmark::DoNotOptimize(bsdf->pdf(wo, wl0, TransportMode::Radiance));
        benchmark::DoNotOptimize(bsdf->sample(wo, rng.uniform(), vec2(rng.uniform(), rng.uniform()), TransportMode::Radiance));
        arena.reset();
    }
}
BENCHMARK(BM_ShadingPoint)->ArgsProduct({{0, 1, 3}, {0, 4}});

void BM_RoughTablesBuild(benchmark::State& state) {
    const auto type = state.range(0) == 0 ? MicrofacetType::Beckmann : MicrofacetType::GGX;
    state.SetLabel(state.range(0) == 0 ? "beckmann" : "ggx");
    for (auto _ : state) benchmark::DoNotOptimize(buildRoughTables(type, RoughTableResolution{}));
}
BENCHMARK(BM_RoughTablesBuild)->DenseRange(0, 1)->Unit(benchmark::kMillisecond)->Iterations(1)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
