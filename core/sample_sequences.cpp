// Sample sequences of the samplers (core/sample_sequences.h).
#include "core/sample_sequences.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>

#include "core/rng.h"
#include "core/sobol_directions.h"

namespace iris {

namespace {

/// The three 32-bit seeds of a Sobol request: the index shuffle's and dimension 0's are the two
/// halves of the request's seed (already a SplitMix64 output, Sampler::nextDimensionSeed),
/// dimension 1's the low half of one more SplitMix64 step.
struct SobolSeeds {
    uint32_t shuffle, dim0;
    explicit SobolSeeds(uint64_t dimensionSeed) : shuffle(uint32_t(dimensionSeed)), dim0(uint32_t(dimensionSeed >> 32)) {}
};
uint32_t sobolDim1Seed(uint64_t dimensionSeed) { return uint32_t(mix64(dimensionSeed)); }

/// One round of an invertible hash of b-bit integers (`mask` = 2^b − 1): xor with a key, multiply by
/// an odd constant and xorshift right, each a bijection modulo 2^b.
uint32_t hashRound(uint32_t i, uint32_t mask, int bits, uint32_t key, uint32_t odd) {
    i = (i ^ key) & mask;
    i = (i * odd) & mask;
    return i ^ (i >> std::max(1, bits / 2));
}

/// A fraction of 2^32 as a float in [0, 1).
float unitFloat(uint32_t bits) { return std::min(kOneMinusEpsilon, float(bits) * 0x1p-32f); }

/// (stratum + jitter) / strata as a float in [0, 1).
float inStratum(uint64_t stratum, float jitter, uint64_t strata) {
    return std::min(kOneMinusEpsilon, float((double(stratum) + double(jitter)) / double(strata)));
}

/// ⌈√n⌉ for n >= 1.
uint32_t ceilSqrt(uint32_t n) {
    uint32_t m = uint32_t(std::sqrt(double(n)));
    while (uint64_t(m) * m < n) ++m;
    while (m > 1 && uint64_t(m - 1) * (m - 1) >= n) --m;
    return m;
}

/// Sobol direction numbers of dimension 1 (primitive polynomial x + 1): m_1 = 1,
/// m_k = 2·m_{k−1} ⊕ m_{k−1}, v_k = m_k / 2^k (Bratley & Fox, ACM TOMS 14(1), 1988, eq. 2–3).
constexpr std::array<uint32_t, 32> sobolDimension1() {
    std::array<uint32_t, 32> v{};
    uint64_t m = 1;
    for (int k = 1; k <= 32; ++k) {
        v[size_t(k - 1)] = uint32_t(m << (32 - k));
        m = (m << 1) ^ m;
    }
    return v;
}

constexpr std::array<uint32_t, 32> kSobol1 = sobolDimension1();

/// Dimension 1 by bytes, its bits reversed: the point is a xor of direction numbers, one per set
/// bit of the index (Bratley & Fox 1988, eq. 4), so it is the xor of the four bytes' partial
/// points; table[j][b] = reverse of the point of index b·2^(8j). Reversed because the scramble
/// works on reversed bits (nestedUniformScramble).
constexpr std::array<std::array<uint32_t, 256>, 4> sobol1ReversedByteTables() {
    std::array<std::array<uint32_t, 256>, 4> t{};
    for (int j = 0; j < 4; ++j)
        for (uint32_t b = 0; b < 256; ++b) {
            uint32_t x = 0;
            for (int k = 0; k < 8; ++k)
                if ((b >> k) & 1u) x ^= kSobol1[size_t(8 * j + k)];
            t[size_t(j)][b] = reverseBits32(x);
        }
    return t;
}

constexpr std::array<std::array<uint32_t, 256>, 4> kSobol1Reversed = sobol1ReversedByteTables();

/// reverseBits32(sobolPointBits(index, 1)) by four table reads (core/sobol_directions.h).
uint32_t sobol1Reversed(uint32_t index) {
    return kSobol1Reversed[0][index & 0xffu] ^ kSobol1Reversed[1][(index >> 8) & 0xffu] ^
           kSobol1Reversed[2][(index >> 16) & 0xffu] ^ kSobol1Reversed[3][index >> 24];
}

/// The hash of nestedUniformScramble on bits already reversed: nestedUniformScramble(x, s) =
/// reverseBits32(scrambleReversed(reverseBits32(x), s)).
uint32_t scrambleReversed(uint32_t x, uint32_t seed) {
    // Burley 2020, listing 3 (the Laine–Karras style hash with the paper's improved constants).
    x += seed;
    x ^= x * 0x6c50b47cu;
    x ^= x * 0xb82f1e52u;
    x ^= x * 0xc7afe638u;
    x ^= x * 0x8d22f6e6u;
    return x;
}

/// The request's shuffled Sobol index nestedUniformScramble(sampleIndex, seed), from the sample
/// index's bits reversed (which a sampler computes once for all its requests).
uint32_t shuffledIndex(uint32_t reversedSampleIndex, uint32_t seed) {
    return reverseBits32(scrambleReversed(reversedSampleIndex, seed));
}

/// The request's index within its pattern of n and the seed of its round ⌊index / n⌋.
struct PatternIndex {
    uint32_t index;
    uint64_t roundSeed;
};

PatternIndex patternIndex(uint64_t sampleIndex, uint32_t n, uint64_t dimensionSeed) {
    return {uint32_t(sampleIndex % n), mix64(dimensionSeed ^ mix64(sampleIndex / n + 0x632be59bd9b4e019ull))};
}

}  // namespace

uint32_t permuteIndex(uint32_t i, uint32_t n, uint64_t seed) {
    if (n <= 1) return 0;
    const int bits = 32 - std::countl_zero(n - 1);
    const uint32_t mask = bits >= 32 ? 0xffffffffu : (1u << bits) - 1u;
    // Independent keys per round: the first round's xor makes the image of any i uniform over
    // the seeds, and each later round is a bijection with a key of its own, so it stays uniform.
    const uint32_t k0 = uint32_t(seed), k1 = uint32_t(seed >> 32), k2 = uint32_t(mix64(seed)), k3 = uint32_t(mix64(seed) >> 32);
    do {  // cycle-walking: a bijection of [0, 2^b) restricted to [0, n) is a bijection of [0, n)
        i = hashRound(i, mask, bits, k0, 0x9e3779b1u);
        i = hashRound(i, mask, bits, k1, 0x85ebca6bu);
        i = hashRound(i, mask, bits, k2, 0xc2b2ae35u);
        i = hashRound(i, mask, bits, k3, 0x27d4eb2fu);
    } while (i >= n);
    // Cycle-walking leaves where an index goes non-uniform over the seeds when n is not a power of
    // two; a seeded rotation of [0, n) after it makes that exactly uniform and keeps the bijection.
    return uint32_t((uint64_t(i) + mix64(seed ^ 0xa0761d6478bd642full) % n) % n);
}

uint32_t nestedUniformScramble(uint32_t x, uint32_t seed) {
    // Applied to the bit-reversed value so that each bit is flipped by a hash of the bits above it.
    return reverseBits32(scrambleReversed(reverseBits32(x), seed));
}

float stratified1D(uint64_t sampleIndex, uint32_t patternSize, uint64_t dimensionSeed, float jitter) {
    const PatternIndex p = patternIndex(sampleIndex, patternSize, dimensionSeed);
    return inStratum(permuteIndex(p.index, patternSize, p.roundSeed), jitter, patternSize);
}

vec2 stratified2D(uint64_t sampleIndex, uint32_t patternSize, uint64_t dimensionSeed, vec2 jitter) {
    const PatternIndex p = patternIndex(sampleIndex, patternSize, dimensionSeed);
    const uint32_t m = ceilSqrt(patternSize);
    const uint32_t cell = permuteIndex(p.index, m * m, p.roundSeed);  // n <= m² distinct cells
    return vec2(inStratum(cell % m, jitter.x, m), inStratum(cell / m, jitter.y, m));
}

vec2 multijitter2D(uint64_t sampleIndex, uint32_t patternSize, uint64_t dimensionSeed, vec2 jitter) {
    const PatternIndex p = patternIndex(sampleIndex, patternSize, dimensionSeed);
    // Kensler 2013, listing 4: an m×k grid of cells (m columns, k rows, m·k >= n) whose points are
    // also stratified in m·k strata along x and along y: x = (column + (s_y + j_x)/k)/m, y = (row +
    // (s_x + j_y)/m)/k with s_x, s_y permutations shared by each column and each row. The cell is
    // drawn from all m·k cells, not from the first n: where m·k > n (n = 8, 32, 128, ...) Kensler's
    // listing fills the last row only partly, which leaves the same corner unsampled in every round
    // (a bias); a permutation of all cells keeps each point uniform and each cell used at most once.
    const uint32_t m = ceilSqrt(patternSize), k = (patternSize + m - 1) / m;
    const uint32_t s = permuteIndex(p.index, m * k, p.roundSeed);
    const uint32_t column = s % m, row = s / m;
    const uint32_t sx = permuteIndex(column, m, mix64(p.roundSeed + 1)), sy = permuteIndex(row, k, mix64(p.roundSeed + 2));
    return vec2(inStratum(uint64_t(column) * k + sy, jitter.x, uint64_t(m) * k),
                inStratum(uint64_t(row) * m + sx, jitter.y, uint64_t(m) * k));
}

// The points are nestedUniformScramble(sobolPointBits(index, d), seed_d) of the shuffled index, written
// with the reversals cancelled: sobolPointBits(index, 0) is reverseBits32(index), so its scramble is
// reverseBits32(scrambleReversed(index, ·)); dimension 1 is read reversed from byte tables. Same
// bits as the plain composition (tests/core/test_sample_sequences.cpp), at a fraction of its cost.
float sobol1DReversed(uint32_t reversedSampleIndex, uint64_t dimensionSeed) {
    const SobolSeeds seeds(dimensionSeed);
    const uint32_t index = shuffledIndex(reversedSampleIndex, seeds.shuffle);
    return unitFloat(reverseBits32(scrambleReversed(index, seeds.dim0)));
}

vec2 sobol2DReversed(uint32_t reversedSampleIndex, uint64_t dimensionSeed) {
    const SobolSeeds seeds(dimensionSeed);
    const uint32_t index = shuffledIndex(reversedSampleIndex, seeds.shuffle);
    return vec2(unitFloat(reverseBits32(scrambleReversed(index, seeds.dim0))),
                unitFloat(reverseBits32(scrambleReversed(sobol1Reversed(index), sobolDim1Seed(dimensionSeed)))));
}

float sobol1D(uint64_t sampleIndex, uint64_t dimensionSeed) {
    return sobol1DReversed(reverseBits32(uint32_t(sampleIndex)), dimensionSeed);
}

vec2 sobol2D(uint64_t sampleIndex, uint64_t dimensionSeed) {
    return sobol2DReversed(reverseBits32(uint32_t(sampleIndex)), dimensionSeed);
}

float highDimSobol(uint32_t sampleIndex, int dimension, uint64_t pixelSeed) {
    const uint32_t seed = uint32_t(mix64(pixelSeed + uint64_t(dimension + 1) * 0xd1b54a32d192ed03ull));
    return unitFloat(nestedUniformScramble(sobolPointBits(sampleIndex, dimension), seed));
}

float Sampler::patterned1D() {
    const uint64_t d = nextDimensionSeed();
    if (pattern_.sequence == SampleSequence::HighDimSobol && sobolDimension_ < kSobolDimensions)
        return highDimSobol(uint32_t(sampleIndex_), sobolDimension_++, pixelSeed_);
    if (pattern_.sequence == SampleSequence::Sobol || pattern_.sequence == SampleSequence::HighDimSobol)
        return sobol1DReversed(reversedIndex_, d);
    return stratified1D(sampleIndex_, pattern_.size, d, jitter());  // stratified and multijitter
}

vec2 Sampler::patterned2D() {
    const uint64_t d = nextDimensionSeed();
    if (pattern_.sequence == SampleSequence::HighDimSobol && sobolDimension_ + 1 < kSobolDimensions) {
        const int j = sobolDimension_;
        sobolDimension_ += 2;
        return vec2(highDimSobol(uint32_t(sampleIndex_), j, pixelSeed_), highDimSobol(uint32_t(sampleIndex_), j + 1, pixelSeed_));
    }
    if (pattern_.sequence == SampleSequence::HighDimSobol) sobolDimension_ = kSobolDimensions;  // the rest padded
    if (pattern_.sequence == SampleSequence::Sobol || pattern_.sequence == SampleSequence::HighDimSobol)
        return sobol2DReversed(reversedIndex_, d);
    const float jx = jitter();
    const vec2 j(jx, jitter());
    return pattern_.sequence == SampleSequence::Multijitter ? multijitter2D(sampleIndex_, pattern_.size, d, j)
                                                            : stratified2D(sampleIndex_, pattern_.size, d, j);
}

}  // namespace iris
