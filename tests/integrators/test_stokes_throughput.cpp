// StokesThroughput (integrators/stokes_throughput.h), whose lane loops run four lanes at a time:
// against the per-lane row · matrix product and rotator on random inputs, equal bit for bit; a wrong
// reference (the transposed matrix) is told apart; non-finite lanes are found in the entries only.
#include <gtest/gtest.h>

#include <limits>
#include <random>

#include "integrators/stokes_throughput.h"
#include "spectral/stokes_basis.h"

using namespace iris;

namespace {

MuellerSpectrum randomMueller(int n, std::mt19937& rng) {
    std::uniform_real_distribution<float> u(-1, 1);
    MuellerSpectrum M(n);
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            for (int l = 0; l < n; ++l) M(i, j)[l] = u(rng);
    return M;
}

/// Row 0 of the throughput after apply(M) from the identity, lane by lane: Σ_i e0(i) M(i, j)
/// summed in order, or of Mᵀ when `transposed` (a wrong reference).
float rowTimesMatrix(const MuellerSpectrum& M, const float x[4], int j, int l, bool transposed) {
    float v = x[0] * (transposed ? M(j, 0) : M(0, j))[l];
    for (int i = 1; i < 4; ++i) v += x[i] * (transposed ? M(j, i) : M(i, j))[l];
    return v;
}

}  // namespace

TEST(StokesThroughput, ApplyEqualsTheLaneByLaneRowProduct) {
    std::mt19937 rng(3);
    for (int trial = 0; trial < 200; ++trial) {
        const int n = 1 + trial % 9;
        StokesThroughput T(1, n, vec3(1, 0, 0));
        const MuellerSpectrum first = randomMueller(n, rng), second = randomMueller(n, rng);
        T.apply(first, vec3(1, 0, 0));
        float x[kMaxWavelengths][4];
        for (int l = 0; l < n; ++l)
            for (int j = 0; j < 4; ++j) x[l][j] = T.at(0, j)[l];
        T.apply(second, vec3(1, 0, 0));
        bool wrongAgrees = true;
        for (int l = 0; l < n; ++l)
            for (int j = 0; j < 4; ++j) {
                ASSERT_EQ(T.at(0, j)[l], rowTimesMatrix(second, x[l], j, l, false)) << trial << " lane " << l;
                wrongAgrees = wrongAgrees && T.at(0, j)[l] == rowTimesMatrix(second, x[l], j, l, true);
            }
        EXPECT_FALSE(wrongAgrees) << trial;
    }
}

TEST(StokesThroughput, ChangeBasisEqualsTheLaneByLaneRotator) {
    std::mt19937 rng(4);
    const int n = 7;
    StokesThroughput T(4, n, vec3(1, 0, 0));
    T.apply(randomMueller(n, rng), vec3(1, 0, 0));
    float before[4][4][kMaxWavelengths];
    for (int k = 0; k < 4; ++k)
        for (int j = 0; j < 4; ++j)
            for (int l = 0; l < n; ++l) before[k][j][l] = T.at(k, j)[l];
    const vec3 forward(0, 0, 1), next = glm::normalize(vec3(1, 2, 0));
    const mueller::BasisRotation R = stokesBasisRotation(forward, next, vec3(1, 0, 0));
    T.changeBasis(forward, next);
    for (int k = 0; k < 4; ++k)
        for (int l = 0; l < n; ++l) {  // rows · rotator: columns 1, 2 → (c r1 − s r2, s r1 + c r2)
            EXPECT_EQ(T.at(k, 1)[l], before[k][1][l] * R.c2 - before[k][2][l] * R.s2);
            EXPECT_EQ(T.at(k, 2)[l], before[k][1][l] * R.s2 + before[k][2][l] * R.c2);
            EXPECT_EQ(T.at(k, 0)[l], before[k][0][l]);
            EXPECT_EQ(T.at(k, 3)[l], before[k][3][l]);
        }
}

TEST(StokesThroughput, NonFiniteIsFoundInTheEntriesNotInThePadding) {
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    const int n = 6;  // lanes 6, 7 are padding
    for (int lane = 0; lane < 8; ++lane)
        for (float bad : {nan, inf, -inf}) {
            StokesThroughput T(1, n, vec3(1, 0, 0));
            MuellerSpectrum M = MuellerSpectrum::absorber(SampledSpectrum(n, 0.5f));
            T.apply(M, vec3(1, 0, 0));
            EXPECT_FALSE(T.hasNonFinite());
            M(2, 3).lanes()[lane] = bad;  // reaches row 0's entry 3 (0 · NaN = NaN, 0 · ∞ = NaN)
            T.apply(M, vec3(1, 0, 0));
            EXPECT_EQ(T.hasNonFinite(), lane < n) << "lane " << lane;
        }
}
