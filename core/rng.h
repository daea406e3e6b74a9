// Random numbers. PCG32 (O'Neill 2014, "PCG: A Family of Simple Fast Space-Efficient Statistically
// Good Algorithms for Random Number Generation", pcg32 XSH-RR variant) and a deterministic
// per-(pixel, sample) sampler, so images do not depend on the thread count or tile order.
#pragma once

#include <cstdint>

#include "core/math.h"
#include "core/sample_sequences.h"

namespace iris {

/// SplitMix64 finaliser (Steele et al. 2014), used to derive independent seeds.
inline uint64_t mix64(uint64_t z) {
    z += 0x9e3779b97f4a7c15ull;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

class Pcg32 {
public:
    Pcg32() { seed(0x853c49e6748fea9bull, 0xda3e39cb94b95bdbull); }
    Pcg32(uint64_t state, uint64_t stream) { seed(state, stream); }

    void seed(uint64_t initState, uint64_t stream) {
        state_ = 0;
        inc_ = (stream << 1u) | 1u;
        nextU32();
        state_ += initState;
        nextU32();
    }

    uint32_t nextU32() {
        const uint64_t old = state_;
        state_ = old * 0x5851f42d4c957f2dull + inc_;
        const uint32_t xorshifted = uint32_t(((old >> 18u) ^ old) >> 27u);
        const uint32_t rot = uint32_t(old >> 59u);
        return (xorshifted >> rot) | (xorshifted << ((~rot + 1u) & 31));
    }

    /// Uniform float in [0, 1).
    float uniform() { return std::min(kOneMinusEpsilon, float(nextU32()) * 0x1p-32f); }
    double uniformDouble() { return double((uint64_t(nextU32()) << 21) ^ nextU32()) * 0x1p-53; }

private:
    uint64_t state_, inc_;
};

/// How a sampler draws its points (render/samplers/, core/sample_sequences.h): the sequence and,
/// for stratified and multijitter, the pattern size n and whether points are jittered inside their
/// strata (false: stratum centres).
struct SamplePattern {
    SampleSequence sequence = SampleSequence::Independent;
    uint32_t size = 1;
    bool jitter = true;
};

/// The sampler of one (pixel, sample index) pair: every value depends only on the render seed, the
/// pixel, the sample index and the request's position in the path's sequence of get1D/get2D calls
/// (its dimension), never on scheduling. Independent: one PCG32 stream per pair. Other sequences:
/// request d takes its point from the sequence with a seed of (seed, pixel, d), jittered with the
/// pair's PCG32 stream; highdimsobol's requests take consecutive dimensions of one Sobol point
/// (core/sample_sequences.h).
class Sampler {
public:
    Sampler(uint64_t seed, uint64_t pixelIndex, uint64_t sampleIndex)
        : rng_(mix64(seed ^ mix64(pixelIndex * 0x9e3779b97f4a7c15ull + sampleIndex)),
               mix64(pixelIndex) ^ seed) {}
    Sampler(uint64_t seed, uint64_t pixelIndex, uint64_t sampleIndex, const SamplePattern& pattern)
        : Sampler(seed, pixelIndex, sampleIndex) {
        pattern_ = pattern;
        pixelSeed_ = mix64(seed ^ mix64(pixelIndex + 0x2545f4914f6cdd1dull));
        sampleIndex_ = sampleIndex;
        reversedIndex_ = reverseBits32(uint32_t(sampleIndex));
    }
    explicit Sampler(uint64_t seed) : rng_(mix64(seed), mix64(seed ^ 0x5851f42d4c957f2dull)) {}

    float get1D() { return pattern_.sequence == SampleSequence::Independent ? rng_.uniform() : patterned1D(); }
    vec2 get2D() {
        if (pattern_.sequence != SampleSequence::Independent) return patterned2D();
        const float a = rng_.uniform();
        return vec2(a, rng_.uniform());
    }

private:
    float patterned1D();
    vec2 patterned2D();
    uint64_t nextDimensionSeed() { return mix64(pixelSeed_ + uint64_t(dimension_++) * 0x9e3779b97f4a7c15ull); }
    float jitter() { return pattern_.jitter ? rng_.uniform() : 0.5f; }

    Pcg32 rng_;
    SamplePattern pattern_;
    uint64_t pixelSeed_ = 0, sampleIndex_ = 0;
    uint32_t reversedIndex_ = 0;  // sobol's start: the sample index's bits reversed
    uint32_t dimension_ = 0;
    int sobolDimension_ = 0;  // highdimsobol: the next joint Sobol dimension
};

}  // namespace iris
