// Mitsuba 3's and 0.6's sampler types (Mitsuba 3 documentation, "Samplers"; Mitsuba 0.6 manual
// §8.12). Each gives the sample count and the sequence of core/sample_sequences.h:
//   independent               independent uniform points (PCG32 per pixel and sample)
//   stratified                strata per request, jitter (default true) inside them
//   multijitter               Kensler's correlated multi-jittered points, jitter (default true)
//   sobol, ldsampler (0.6)    Owen-scrambled Sobol points (Burley 2020); 0.6's ldsampler drew
//                             (0,2)-sequence points, which these are too
//   highdimsobol              the first 32 Sobol dimensions jointly, Owen-scrambled per pixel
//                             (iris's own name; Mitsuba 0.6's `sobol` is a high-dimensional Sobol
//                             sampler too, but iris keeps `sobol` for the padded points above)
//   orthogonal, halton, hammersley: accepted for their sample_count, drawn as independent (iris
//                             has no orthogonal-array, Halton or Hammersley sequence yet).
// seed, dimension and scramble are accepted and do not change the points: every sequence is
// seeded by the render seed (render --seed), and the dimension count has no limit.
#include "render/samplers/sampler_description.h"

#include "core/error.h"

namespace iris {

namespace {

constexpr int kMaxSamples = 1 << 24;

std::shared_ptr<SamplerDescription> describe(const Properties& p, SampleSequence sequence) {
    auto d = std::make_shared<SamplerDescription>();
    d->sampleCount = p.getInt("sample_count", 4);
    if (d->sampleCount < 1 || d->sampleCount > kMaxSamples)
        failAt(p.locationOf("sample_count"), "sample_count must be in 1..", kMaxSamples);
    d->pattern.sequence = sequence;
    p.getInt("seed", 0);
    p.getInt("dimension", 0);
    p.getInt("scramble", -1);
    return d;
}

/// A sampler without jittered strata (independent, sobol): Mitsuba 0.6's samplers accept `jitter`.
template <SampleSequence S>
std::shared_ptr<SamplerDescription> unjitteredSampler(const Properties& p) {
    p.getBool("jitter", true);
    return describe(p, S);
}

template <SampleSequence S>
std::shared_ptr<SamplerDescription> jitteredSampler(const Properties& p) {
    auto d = describe(p, S);
    d->pattern.jitter = p.getBool("jitter", true);
    return d;
}

constexpr std::pair<SampleSequence, const char*> kNames[] = {{SampleSequence::Independent, "independent"},
                                                             {SampleSequence::Stratified, "stratified"},
                                                             {SampleSequence::Multijitter, "multijitter"},
                                                             {SampleSequence::Sobol, "sobol"},
                                                             {SampleSequence::HighDimSobol, "highdimsobol"}};

}  // namespace

SampleSequence sampleSequenceNamed(const std::string& name) {
    for (const auto& [s, n] : kNames)
        if (name == n) return s;
    fail("unknown sampler '", name, "' (supported: independent, stratified, multijitter, sobol, highdimsobol)");
}

const char* sampleSequenceName(SampleSequence s) {
    for (const auto& [seq, n] : kNames)
        if (seq == s) return n;
    return "independent";
}

IRIS_REGISTER(SamplerRegistry, "independent", unjitteredSampler<SampleSequence::Independent>);
IRIS_REGISTER(SamplerRegistry, "stratified", jitteredSampler<SampleSequence::Stratified>);
IRIS_REGISTER(SamplerRegistry, "multijitter", jitteredSampler<SampleSequence::Multijitter>);
IRIS_REGISTER(SamplerRegistry, "sobol", unjitteredSampler<SampleSequence::Sobol>);
IRIS_REGISTER(SamplerRegistry, "ldsampler", unjitteredSampler<SampleSequence::Sobol>);
IRIS_REGISTER(SamplerRegistry, "highdimsobol", unjitteredSampler<SampleSequence::HighDimSobol>);
IRIS_REGISTER(SamplerRegistry, "orthogonal", unjitteredSampler<SampleSequence::Independent>);
IRIS_REGISTER(SamplerRegistry, "halton", unjitteredSampler<SampleSequence::Independent>);
IRIS_REGISTER(SamplerRegistry, "hammersley", unjitteredSampler<SampleSequence::Independent>);

}  // namespace iris
