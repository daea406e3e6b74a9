// Mitsuba 3's and 0.6's sampler types. Each is read for its sample_count only: the renderer uses
// its own sample sequence (independent PCG32 streams per pixel and sample index), so a scene's
// choice of stratified or low-discrepancy points changes the noise pattern in Mitsuba, not the
// expected image; their other parameters are accepted.
#include "render/samplers/sampler_description.h"

namespace iris {

namespace {

constexpr int kMaxSamples = 1 << 24;

std::shared_ptr<SamplerDescription> createSampler(const Properties& p) {
    auto d = std::make_shared<SamplerDescription>();
    d->sampleCount = p.getInt("sample_count", 4);
    if (d->sampleCount < 1 || d->sampleCount > kMaxSamples)
        failAt(p.locationOf("sample_count"), "sample_count must be in 1..", kMaxSamples);
    p.getInt("seed", 0);
    p.getInt("dimension", 0);
    p.getBool("jitter", true);
    p.getInt("scramble", -1);
    return d;
}

}  // namespace

IRIS_REGISTER(SamplerRegistry, "independent", createSampler);
IRIS_REGISTER(SamplerRegistry, "stratified", createSampler);
IRIS_REGISTER(SamplerRegistry, "multijitter", createSampler);
IRIS_REGISTER(SamplerRegistry, "orthogonal", createSampler);
IRIS_REGISTER(SamplerRegistry, "ldsampler", createSampler);
IRIS_REGISTER(SamplerRegistry, "halton", createSampler);
IRIS_REGISTER(SamplerRegistry, "hammersley", createSampler);
IRIS_REGISTER(SamplerRegistry, "sobol", createSampler);

}  // namespace iris
