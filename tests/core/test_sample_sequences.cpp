// The samplers' sequences (core/sample_sequences.h): known Sobol points, bijective permutations and
// scrambles, stratification of every pattern (1D strata, 2D cells, Sobol's elementary intervals),
// uniformity across pixels and dimensions, and the Sampler class's determinism. The stratification
// check is shown to fail on independent points.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <set>
#include <vector>

#include "core/rng.h"
#include "core/sample_sequences.h"
#include "core/sobol_directions.h"

using namespace iris;

namespace {

/// True if each of `strata` equal intervals of [0, 1) holds exactly one of `values` (strata ==
/// values.size()).
bool eachStratumOnce(const std::vector<float>& values, size_t strata) {
    std::vector<int> hits(strata, 0);
    for (float v : values) {
        if (!(v >= 0.0f && v < 1.0f)) return false;
        ++hits[std::min(strata - 1, size_t(double(v) * double(strata)))];
    }
    return std::all_of(hits.begin(), hits.end(), [](int h) { return h == 1; });
}

/// True if each cell of a cols × rows grid holds exactly one point (cols · rows == points).
bool eachCellOnce(const std::vector<vec2>& points, size_t cols, size_t rows) {
    std::vector<int> hits(cols * rows, 0);
    for (const vec2& p : points) {
        const size_t cx = std::min(cols - 1, size_t(double(p.x) * double(cols)));
        const size_t cy = std::min(rows - 1, size_t(double(p.y) * double(rows)));
        ++hits[cy * cols + cx];
    }
    return std::all_of(hits.begin(), hits.end(), [](int h) { return h == 1; });
}

std::vector<float> xs(const std::vector<vec2>& p, int axis) {
    std::vector<float> out;
    for (const vec2& v : p) out.push_back(v[axis]);
    return out;
}

using Points2D = std::function<vec2(uint64_t index, uint64_t seed)>;
using Points1D = std::function<float(uint64_t index, uint64_t seed)>;

std::vector<vec2> points2D(const Points2D& f, uint64_t first, uint64_t count, uint64_t seed) {
    std::vector<vec2> p;
    for (uint64_t i = first; i < first + count; ++i) p.push_back(f(i, seed));
    return p;
}

std::vector<float> points1D(const Points1D& f, uint64_t first, uint64_t count, uint64_t seed) {
    std::vector<float> p;
    for (uint64_t i = first; i < first + count; ++i) p.push_back(f(i, seed));
    return p;
}

/// Independent uniform points (the baseline that the stratification checks must reject).
vec2 independentPoint(uint64_t i, uint64_t seed) {
    Sampler s(seed, 0, i);
    return s.get2D();
}

}  // namespace

TEST(SampleSequences, SobolMatchesTheKnownFirstPoints) {
    // Sobol 1967 / Bratley & Fox 1988: dimension 0 is van der Corput's sequence; dimension 1
    // (polynomial x + 1, v = 1/2, 3/4, 5/8, ...) in index order (not Gray-code order) starts
    // 0, 1/2, 3/4, 1/4, 5/8, 1/8, 3/8, 7/8.
    const double d0[] = {0, 0.5, 0.25, 0.75, 0.125, 0.625, 0.375, 0.875};
    const double d1[] = {0, 0.5, 0.75, 0.25, 0.625, 0.125, 0.375, 0.875};
    for (uint32_t i = 0; i < 8; ++i) {
        EXPECT_EQ(sobolPointBits(i, 0) * 0x1p-32, d0[i]) << i;
        EXPECT_EQ(sobolPointBits(i, 1) * 0x1p-32, d1[i]) << i;
    }
}

namespace {

/// sobol2D as core/sample_sequences.h defines it, composed plainly: the shuffled index
/// nestedUniformScramble(i, s0), each dimension's sobolPointBits Owen-scrambled with its own seed (s0
/// and s1 the low and high halves of the request's seed, s2 the low half of its SplitMix64);
/// `wrong` puts dimension 0's bits in both coordinates (a definition the fast path must not match).
vec2 plainSobol2D(uint64_t i, uint64_t seed, bool wrong = false) {
    const auto part = [&](int k) { return k == 0 ? uint32_t(seed) : k == 1 ? uint32_t(seed >> 32) : uint32_t(mix64(seed)); };
    const uint32_t index = nestedUniformScramble(uint32_t(i), part(0));
    const auto unit = [](uint32_t b) { return std::min(kOneMinusEpsilon, float(b) * 0x1p-32f); };
    return vec2(unit(nestedUniformScramble(sobolPointBits(index, 0), part(1))),
                unit(nestedUniformScramble(sobolPointBits(index, wrong ? 0 : 1), part(2))));
}

}  // namespace

TEST(SampleSequences, FastSobolEqualsThePlainComposition) {
    // sobol1D/sobol2D cancel the bit reversals and read dimension 1 from byte tables; the points
    // must be the plain definition's, bit for bit, for small and large indices and any seed.
    Pcg32 rng(5, 11);
    int wrongAgrees = 0;
    for (int n = 0; n < 20000; ++n) {
        const uint64_t i = n < 1000 ? uint64_t(n) : uint64_t(rng.nextU32()) | (n % 3 == 0 ? uint64_t(rng.nextU32()) << 32 : 0);
        const uint64_t seed = (uint64_t(rng.nextU32()) << 32) | rng.nextU32();
        const vec2 fast = sobol2D(i, seed), plain = plainSobol2D(i, seed);
        ASSERT_EQ(fast.x, plain.x) << "index " << i << " seed " << seed;
        ASSERT_EQ(fast.y, plain.y) << "index " << i << " seed " << seed;
        ASSERT_EQ(sobol1D(i, seed), plain.x) << "index " << i << " seed " << seed;
        const vec2 fromReversed = sobol2DReversed(reverseBits32(uint32_t(i)), seed);  // the Sampler's path
        ASSERT_EQ(fromReversed.x, plain.x);
        ASSERT_EQ(fromReversed.y, plain.y);
        ASSERT_EQ(sobol1DReversed(reverseBits32(uint32_t(i)), seed), plain.x);
        wrongAgrees += sobol2D(i, seed).y == plainSobol2D(i, seed, true).y;
    }
    EXPECT_LT(wrongAgrees, 10);  // the control: another dimension's bits are told apart
}

TEST(SampleSequences, PermutationIsABijectionThatDependsOnTheSeed) {
    for (uint32_t n : {1u, 2u, 3u, 7u, 16u, 100u, 1000u, 4097u}) {
        for (uint64_t seed : {0ull, 1ull, 0x123456789abcdefull}) {
            std::set<uint32_t> image;
            for (uint32_t i = 0; i < n; ++i) {
                const uint32_t p = permuteIndex(i, n, seed);
                ASSERT_LT(p, n);
                image.insert(p);
            }
            EXPECT_EQ(image.size(), n) << "n " << n << " seed " << seed;
        }
    }
    int differ = 0;
    for (uint32_t i = 0; i < 100; ++i) differ += permuteIndex(i, 100, 1) != permuteIndex(i, 100, 2);
    EXPECT_GT(differ, 80);
    // Over the seeds, where one index goes is uniform (chi-square with 15 and 11 degrees of
    // freedom; their 1e-4 upper quantiles are 42.3 and 35.6). A first version reused its keys
    // across rounds and left 4 of 16 places empty; cycle-walking alone was non-uniform for 12.
    for (auto [n, quantile] : {std::pair{16u, 42.3}, std::pair{12u, 35.6}}) {
        std::vector<int> hits(n, 0);
        const int seeds = 1000 * int(n);
        for (int s = 0; s < seeds; ++s) ++hits[permuteIndex(3, n, mix64(uint64_t(s)))];
        double chi2 = 0;
        for (int h : hits) chi2 += (h - 1000.0) * (h - 1000.0) / 1000.0;
        EXPECT_LT(chi2, quantile) << n;
    }
}

TEST(SampleSequences, OwenScramblingPermutesAlignedBlocks) {
    // Each bit is flipped by a hash of the bits above it: the top 12 bits of 4096 values that
    // differ only there are again all 4096 values.
    for (uint32_t seed : {0u, 7u, 0xdeadbeefu}) {
        std::set<uint32_t> tops;
        for (uint32_t i = 0; i < 4096; ++i) tops.insert(nestedUniformScramble(i << 20, seed) >> 20);
        EXPECT_EQ(tops.size(), 4096u);
    }
    EXPECT_NE(nestedUniformScramble(0, 1), nestedUniformScramble(0, 2));
}

TEST(SampleSequences, StratifiedCoversEveryStratumAndCell) {
    const Points1D s1 = [](uint64_t i, uint64_t seed) { return stratified1D(i, 64, seed, 0.3f); };
    const Points2D s2 = [](uint64_t i, uint64_t seed) { return stratified2D(i, 64, seed, vec2(0.7f, 0.2f)); };
    for (uint64_t seed : {1ull, 99ull}) {
        EXPECT_TRUE(eachStratumOnce(points1D(s1, 0, 64, seed), 64));
        EXPECT_TRUE(eachStratumOnce(points1D(s1, 64, 64, seed), 64));  // the next round
        EXPECT_TRUE(eachCellOnce(points2D(s2, 0, 64, seed), 8, 8));
        EXPECT_TRUE(eachCellOnce(points2D(s2, 128, 64, seed), 8, 8));
    }
    // A pattern size that is not a square: 50 samples in 50 distinct cells of the 8×8 grid.
    std::set<int> cells;
    for (uint64_t i = 0; i < 50; ++i) {
        const vec2 p = stratified2D(i, 50, 5, vec2(0.5f));
        cells.insert(int(p.x * 8) + 8 * int(p.y * 8));
    }
    EXPECT_EQ(cells.size(), 50u);
    // Without jitter the points sit at stratum centres.
    EXPECT_FLOAT_EQ(std::fmod(stratified1D(3, 4, 1, 0.5f) * 4.0f, 1.0f), 0.5f);
}

TEST(SampleSequences, MultijitterIsStratifiedInCellsAndAlongEachAxis) {
    const Points2D mj = [](uint64_t i, uint64_t seed) { return multijitter2D(i, 64, seed, vec2(0.4f, 0.9f)); };
    for (uint64_t seed : {3ull, 12345ull}) {
        const std::vector<vec2> p = points2D(mj, 0, 64, seed);
        EXPECT_TRUE(eachCellOnce(p, 8, 8));
        EXPECT_TRUE(eachStratumOnce(xs(p, 0), 64));
        EXPECT_TRUE(eachStratumOnce(xs(p, 1), 64));
    }
    // 56 = 8 columns × 7 rows.
    const Points2D mj56 = [](uint64_t i, uint64_t seed) { return multijitter2D(i, 56, seed, vec2(0.5f)); };
    const std::vector<vec2> p = points2D(mj56, 0, 56, 8);
    EXPECT_TRUE(eachCellOnce(p, 8, 7));
    EXPECT_TRUE(eachStratumOnce(xs(p, 0), 56));
    EXPECT_TRUE(eachStratumOnce(xs(p, 1), 56));
}

TEST(SampleSequences, EveryMultijitterPointIsUniformForAnyPatternSize) {
    // Over the seeds and jitters, each point of a pattern is uniform on the square, also where the m × k
    // grid has more cells than the pattern has points (8 = 3 × 3 − 1, 32 = 6 × 6 − 4, 50, 128 =
    // 12 × 11 − 4). Chi-square of 64 000 seeds in 8 × 8 cells: 63 degrees of freedom, 1e-4 upper
    // quantile 113.6 (Wilson–Hilferty). A first version drew each point's cell from the first n of
    // the m·k cells, so the same corner cells were never sampled: biased (chi-square > 4000 here).
    for (uint32_t n : {8u, 32u, 50u, 64u, 128u}) {
        for (uint64_t index : {uint64_t(0), uint64_t(3), uint64_t(n - 1), uint64_t(n + 5)}) {
            std::vector<int> hits(64, 0);
            const int seeds = 64000;
            for (int s = 0; s < seeds; ++s) {
                const uint64_t j = mix64(uint64_t(s) ^ 0x5bd1e995ull);  // the jitter, uniform too
                const vec2 jitter(float(uint32_t(j) >> 8) * 0x1p-24f, float(uint32_t(j >> 32) >> 8) * 0x1p-24f);
                const vec2 p = multijitter2D(index, n, mix64(uint64_t(s) + 17), jitter);
                ++hits[size_t(std::min(int(p.x * 8), 7) + 8 * std::min(int(p.y * 8), 7))];
            }
            double chi2 = 0;
            for (int h : hits) chi2 += (h - 1000.0) * (h - 1000.0) / 1000.0;
            EXPECT_LT(chi2, 113.6) << "n " << n << " index " << index;
        }
    }
}

TEST(SampleSequences, SobolIsANetInEveryAlignedBlock) {
    const Points2D sobol = [](uint64_t i, uint64_t seed) { return sobol2D(i, seed); };
    const Points1D sobol1 = [](uint64_t i, uint64_t seed) { return sobol1D(i, seed); };
    for (uint64_t seed : {0ull, 42ull}) {
        for (uint64_t first : {0ull, 256ull, 768ull}) {
            const std::vector<vec2> p = points2D(sobol, first, 256, seed);
            for (int a = 0; a <= 8; ++a) EXPECT_TRUE(eachCellOnce(p, size_t(1) << a, size_t(1) << (8 - a))) << a;
            EXPECT_TRUE(eachStratumOnce(points1D(sobol1, first, 256, seed), 256));
        }
        // Every prefix of power-of-two length too.
        for (int k = 0; k <= 6; ++k) EXPECT_TRUE(eachStratumOnce(xs(points2D(sobol, 0, 1u << k, seed), 1), size_t(1) << k)) << k;
    }
}

TEST(SampleSequences, JoeKuoRowsArePrimitivePolynomialsWithValidInitialNumbers) {
    // A typo in the table shows here: each row's polynomial x^s + a_1 x^(s−1) + … + 1 must be
    // primitive over GF(2) (x has order 2^s − 1 modulo it), each m_k odd and below 2^k.
    int rowsChecked = 0;
    for (const SobolPolynomial& row : kJoeKuoRows) {
        const int s = row.degree;
        const uint32_t poly = (1u << s) | (row.a << 1) | 1u;
        uint32_t x = 1, order = 0;
        do {  // multiply by x modulo poly until 1 comes back
            x <<= 1;
            if (x & (1u << s)) x ^= poly;
            ++order;
        } while (x != 1u && order <= (1u << s));
        EXPECT_EQ(order, (1u << s) - 1u) << "row " << rowsChecked + 2;
        for (int k = 0; k < s; ++k) {
            EXPECT_EQ(row.m[size_t(k)] & 1u, 1u) << "row " << rowsChecked + 2 << " m_" << k + 1;
            EXPECT_LT(row.m[size_t(k)], 1u << (k + 1)) << "row " << rowsChecked + 2 << " m_" << k + 1;
        }
        ++rowsChecked;
    }
    EXPECT_EQ(rowsChecked, kSobolDimensions - 1);
    // A wrong polynomial is rejected: x^2 + 1 = (x + 1)^2 is not primitive (x has order 2, not 3).
    uint32_t x = 1, order = 0;
    do {
        x <<= 1;
        if (x & 4u) x ^= 0b101u;
        ++order;
    } while (x != 1u && order <= 4u);
    EXPECT_NE(order, 3u);
}

TEST(SampleSequences, SobolDimensionZeroIsVanDerCorputAndEachDimensionIsStratified) {
    for (uint32_t i = 0; i < 1024; ++i) ASSERT_EQ(sobolPointBits(i, 0), reverseBits32(i)) << i;  // van der Corput
    // Every dimension alone is a (0, m, 1)-net: its first 2^m points fill 2^m strata once each.
    for (int d = 0; d < kSobolDimensions; ++d) {
        std::vector<float> v;
        for (uint32_t i = 0; i < 512; ++i) v.push_back(float(sobolPointBits(i, d) * 0x1p-32));
        EXPECT_TRUE(eachStratumOnce(v, 512)) << d;
    }
}

TEST(SampleSequences, OnlySobolsFirstTwoDimensionsAreAZeroNetAtEverySize) {
    // The trade-off behind highdimsobol (docs/rendering.md, Samplers): its 2D requests get later
    // pairs of dimensions, each with t > 0 at some size 2^m, where sobol's get dimensions 0 and 1.
    const auto isZeroNet = [](int d1, int d2, int m) {
        const uint32_t n = 1u << m;
        for (int a = 0; a <= m; ++a) {
            std::vector<int> hits(n, 0);
            for (uint32_t i = 0; i < n; ++i) {
                const uint32_t x = a ? sobolPointBits(i, d1) >> (32 - a) : 0u;
                const uint32_t y = a < m ? sobolPointBits(i, d2) >> (32 - (m - a)) : 0u;
                if (++hits[(x << (m - a)) | y] > 1) return false;
            }
        }
        return true;
    };
    for (int d1 = 0; d1 < kSobolDimensions; ++d1)
        for (int d2 = d1 + 1; d2 < kSobolDimensions; ++d2) {
            bool always = true;
            for (int m = 1; m <= 9 && always; ++m) always = isZeroNet(d1, d2, m);
            EXPECT_EQ(always, d1 == 0 && d2 == 1) << d1 << ", " << d2;
        }
}

namespace {

/// The first `count` samples of one pixel of a sampler of `seq`: a 1D request, then 2D requests.
std::vector<std::vector<float>> samplerCoordinates(SampleSequence seq, uint64_t pixel, uint32_t count, int requests2D) {
    std::vector<std::vector<float>> out;
    for (uint32_t i = 0; i < count; ++i) {
        Sampler s(11, pixel, i, SamplePattern{seq, count, true});
        std::vector<float> c{s.get1D()};
        for (int r = 0; r < requests2D; ++r) {
            const vec2 p = s.get2D();
            c.push_back(p.x);
            c.push_back(p.y);
        }
        out.push_back(c);
    }
    return out;
}

}  // namespace

TEST(SampleSequences, HighDimSobolIsJointlyStratifiedAcrossRequests) {
    // highdimsobol's dimensions 0 (a 1D request) and 1 (the next 2D request's x) are Sobol's first
    // two, a (0, 8, 2)-net over 256 samples after Owen scrambling: every 2^a × 2^(8−a) grid holds one
    // point per cell. `sobol`'s padded requests are stratified only within a request: across two
    // requests the same check fails (the comparison this sampler exists for).
    for (uint64_t pixel : {0ull, 77ull}) {
        const auto c = samplerCoordinates(SampleSequence::HighDimSobol, pixel, 256, 20);
        std::vector<vec2> across;
        for (const auto& v : c) across.push_back(vec2(v[0], v[1]));
        for (int a = 0; a <= 8; ++a) EXPECT_TRUE(eachCellOnce(across, size_t(1) << a, size_t(1) << (8 - a))) << a;
        // Every joint dimension alone, and the padded ones past the last, stay stratified.
        for (size_t d = 0; d < c[0].size(); ++d) {
            std::vector<float> v;
            for (const auto& x : c) v.push_back(x[d]);
            EXPECT_TRUE(eachStratumOnce(v, 256)) << "coordinate " << d;
        }
    }
    const auto padded = samplerCoordinates(SampleSequence::Sobol, 0, 256, 1);
    std::vector<vec2> across;
    for (const auto& v : padded) across.push_back(vec2(v[0], v[1]));
    bool allGrids = true;
    for (int a = 0; a <= 8; ++a) allGrids = allGrids && eachCellOnce(across, size_t(1) << a, size_t(1) << (8 - a));
    EXPECT_FALSE(allGrids);
}

TEST(SampleSequences, TheStratificationChecksRejectIndependentPoints) {
    const std::vector<vec2> p = points2D(independentPoint, 0, 64, 1);
    EXPECT_FALSE(eachCellOnce(p, 8, 8));
    EXPECT_FALSE(eachStratumOnce(xs(p, 0), 64));
}

TEST(SampleSequences, PointsAreUniformAcrossPixelsAndIndependentAcrossDimensions) {
    // Chi-square of 20 000 pixels' values of one request in 10×10 cells of two consecutive
    // dimensions (the pair a path uses for two bounces): 99 degrees of freedom; its 1e-4 upper
    // quantile is 155.
    for (SampleSequence seq : {SampleSequence::Stratified, SampleSequence::Multijitter, SampleSequence::Sobol,
                               SampleSequence::HighDimSobol}) {
        std::vector<int> hits(100, 0);
        const int pixels = 20000;
        for (int px = 0; px < pixels; ++px) {
            Sampler s(7, uint64_t(px), 3, SamplePattern{seq, 16, true});
            s.get2D();  // dimension 0
            const float a = s.get1D(), b = s.get1D();
            ++hits[size_t(int(a * 10) + 10 * int(b * 10))];
        }
        double chi2 = 0;
        for (int h : hits) chi2 += (h - pixels / 100.0) * (h - pixels / 100.0) / (pixels / 100.0);
        EXPECT_LT(chi2, 155.0) << int(seq);
    }
}

TEST(SampleSequences, SamplerIsDeterministicAndIndependentKeepsItsStream) {
    Sampler a(5, 17, 3), b(5, 17, 3, SamplePattern{});
    for (int i = 0; i < 10; ++i) EXPECT_EQ(a.get1D(), b.get1D());  // images of earlier versions stay
    for (SampleSequence seq : {SampleSequence::Stratified, SampleSequence::Multijitter, SampleSequence::Sobol,
                               SampleSequence::HighDimSobol}) {
        Sampler x(5, 17, 3, SamplePattern{seq, 16, true}), y(5, 17, 3, SamplePattern{seq, 16, true});
        Sampler otherPixel(5, 18, 3, SamplePattern{seq, 16, true});
        for (int i = 0; i < 6; ++i) {
            const vec2 p = x.get2D(), q = y.get2D(), r = otherPixel.get2D();
            EXPECT_EQ(p, q);
            EXPECT_NE(p, r);
        }
    }
}
