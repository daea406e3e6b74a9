// The sample sequences of the samplers (render/samplers/): for one pixel, one dimension (a 1D or
// 2D request of the path) and a sample index, the point that sample uses. Every function is pure:
// the point depends only on its arguments, so images stay bit-identical for any thread count, and
// resumed or split renders equal uninterrupted ones.
//  - stratified: n samples over n strata (1D) or an m×m grid, m = ⌈√n⌉ (2D); each dimension visits
//    its strata in its own random order (a hashed permutation), jittered inside the stratum.
//  - multijitter: Kensler's correlated multi-jittered 2D points ("Correlated Multi-Jittered
//    Sampling", Pixar tech memo 13-01, 2013): stratified on an m×k grid and in n strata along
//    each axis at once; 1D requests as stratified.
//  - sobol: the first two dimensions of the Sobol sequence (Sobol 1967; direction numbers of the
//    polynomials 1 and x + 1), each request with its own Owen scrambling and index shuffling by
//    hashed nested uniform scrambling (Burley, "Practical Hash-based Owen Scrambling", JCGT 9(4),
//    2020): every aligned block of 2^k consecutive sample indices is a (0, k, 2)-net in each 2D
//    request and stratified in 2^k strata in each 1D request. No pattern size: any number works.
//  - highdimsobol: the first kSobolDimensions dimensions of the Sobol sequence jointly (Joe & Kuo
//    2008 direction numbers, core/sobol_directions.h), 1D requests taking one dimension and 2D
//    requests two, in the order the path asks; each dimension Owen-scrambled with a seed of its
//    own per pixel (Burley 2020's hash), the sample index unshuffled. Owen scrambling keeps the
//    sequence's net properties (Owen 1995), so every aligned block of 2^k samples of a pixel is a
//    (t, k, s)-net over all its first dimensions together, not only within each request as
//    `sobol`'s padded points are: the joint stratification behind quasi-Monte Carlo's faster
//    convergence on smooth integrands. Requests past the last dimension take `sobol`'s points.
// Sample indices at or beyond the pattern size n of stratified and multijitter start a new,
// independently permuted pattern ("round" ⌊index / n⌋).
#pragma once

#include <cstdint>

#include "core/math.h"

namespace iris {

enum class SampleSequence { Independent, Stratified, Multijitter, Sobol, HighDimSobol };

/// A bijection of [0, n) chosen by `seed` (an invertible hash of ⌈log2 n⌉-bit integers, cycle-walked
/// into [0, n) as Kensler 2013, section 3, does, with a hash of our own, then rotated by a seeded
/// offset). For each i its image is uniform over the seeds.
uint32_t permuteIndex(uint32_t i, uint32_t n, uint64_t seed);

/// The 32 bits of x in reverse order (bit 0 becomes bit 31).
constexpr uint32_t reverseBits32(uint32_t x) {
    x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
    x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
    x = ((x >> 4) & 0x0f0f0f0fu) | ((x & 0x0f0f0f0fu) << 4);
    x = ((x >> 8) & 0x00ff00ffu) | ((x & 0x00ff00ffu) << 8);
    return (x >> 16) | (x << 16);
}

/// Owen scrambling of a 32-bit fraction by the hashed nested uniform scramble (Burley 2020, §3–4).
uint32_t nestedUniformScramble(uint32_t x, uint32_t seed);

/// The point of a 1D / 2D request. `dimensionSeed` identifies the (seed, pixel, request); `jitter`
/// (in [0,1)^2) places the point inside its stratum (0.5 centres it); `patternSize` n >= 1.
float stratified1D(uint64_t sampleIndex, uint32_t patternSize, uint64_t dimensionSeed, float jitter);
vec2 stratified2D(uint64_t sampleIndex, uint32_t patternSize, uint64_t dimensionSeed, vec2 jitter);
vec2 multijitter2D(uint64_t sampleIndex, uint32_t patternSize, uint64_t dimensionSeed, vec2 jitter);
float sobol1D(uint64_t sampleIndex, uint64_t dimensionSeed);
vec2 sobol2D(uint64_t sampleIndex, uint64_t dimensionSeed);
/// The same points from reverseBits32(uint32_t(sampleIndex)), which a sampler computes once for
/// all its requests (Sampler, core/rng.h).
float sobol1DReversed(uint32_t reversedSampleIndex, uint64_t dimensionSeed);
vec2 sobol2DReversed(uint32_t reversedSampleIndex, uint64_t dimensionSeed);
/// highdimsobol's coordinate in Sobol dimension `dimension` (< kSobolDimensions) of a pixel's
/// sample: sobolPointBits(sampleIndex, dimension) Owen-scrambled with a seed of (pixelSeed, dimension).
float highDimSobol(uint32_t sampleIndex, int dimension, uint64_t pixelSeed);

}  // namespace iris
