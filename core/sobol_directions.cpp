// Sobol direction numbers (core/sobol_directions.h).
#include "core/sobol_directions.h"

#include <cstddef>

namespace iris {

// new-joe-kuo-6.21201, rows d = 2 .. 32: {s, a, {m_1 .. m_s}} (Joe & Kuo 2008; published data).
constexpr std::array<SobolPolynomial, kSobolDimensions - 1> kJoeKuoRows = {{
    {1, 0, {1}},
    {2, 1, {1, 3}},
    {3, 1, {1, 3, 1}},
    {3, 2, {1, 1, 1}},
    {4, 1, {1, 1, 3, 3}},
    {4, 4, {1, 3, 5, 13}},
    {5, 2, {1, 1, 5, 5, 17}},
    {5, 4, {1, 1, 5, 5, 5}},
    {5, 7, {1, 1, 7, 11, 19}},
    {5, 11, {1, 1, 5, 1, 1}},
    {5, 13, {1, 1, 1, 3, 11}},
    {5, 14, {1, 3, 5, 5, 31}},
    {6, 1, {1, 3, 3, 9, 7, 49}},
    {6, 13, {1, 1, 1, 15, 21, 21}},
    {6, 16, {1, 3, 1, 13, 27, 49}},
    {6, 19, {1, 1, 1, 15, 7, 5}},
    {6, 22, {1, 3, 1, 15, 13, 25}},
    {6, 25, {1, 1, 5, 5, 19, 61}},
    {7, 1, {1, 3, 7, 11, 23, 15, 103}},
    {7, 4, {1, 3, 7, 13, 13, 15, 69}},
    {7, 7, {1, 1, 3, 13, 7, 35, 63}},
    {7, 8, {1, 3, 5, 9, 1, 25, 53}},
    {7, 14, {1, 3, 1, 13, 9, 35, 107}},
    {7, 19, {1, 3, 1, 5, 27, 61, 31}},
    {7, 21, {1, 1, 5, 11, 19, 41, 61}},
    {7, 28, {1, 3, 5, 3, 3, 13, 69}},
    {7, 31, {1, 1, 7, 13, 1, 19, 1}},
    {7, 32, {1, 3, 7, 5, 13, 19, 59}},
    {7, 37, {1, 1, 3, 9, 25, 29, 41}},
    {7, 41, {1, 3, 5, 13, 23, 1, 55}},
    {7, 42, {1, 3, 7, 3, 13, 59, 17}},
}};

namespace {

constexpr std::array<std::array<uint32_t, 32>, kSobolDimensions> makeDirections() {
    std::array<std::array<uint32_t, 32>, kSobolDimensions> v{};
    for (int k = 0; k < 32; ++k) v[0][std::size_t(k)] = 1u << (31 - k);  // van der Corput: m_k = 1
    for (int d = 1; d < kSobolDimensions; ++d) {
        const SobolPolynomial& row = kJoeKuoRows[std::size_t(d - 1)];
        const int s = row.degree;
        std::array<uint32_t, 32>& vd = v[std::size_t(d)];
        // v_k = m_k / 2^k for k <= s (index k − 1 here), then Bratley & Fox eq. 3 on the 32-bit
        // fractions: v_k = v_{k−s} ⊕ (v_{k−s} >> s) ⊕ a_1 v_{k−1} ⊕ … ⊕ a_{s−1} v_{k−s+1}.
        for (int k = 0; k < s && k < 32; ++k) vd[std::size_t(k)] = row.m[std::size_t(k)] << (31 - k);
        for (int k = s; k < 32; ++k) {
            uint32_t x = vd[std::size_t(k - s)] ^ (vd[std::size_t(k - s)] >> s);
            for (int j = 1; j < s; ++j)
                if ((row.a >> (s - 1 - j)) & 1u) x ^= vd[std::size_t(k - j)];
            vd[std::size_t(k)] = x;
        }
    }
    return v;
}

}  // namespace

constexpr std::array<std::array<uint32_t, 32>, kSobolDimensions> kSobolDirections = makeDirections();

uint32_t sobolPointBits(uint32_t index, int dimension) {
    const std::array<uint32_t, 32>& v = kSobolDirections[std::size_t(dimension)];
    uint32_t x = 0;
    for (int k = 0; index; ++k, index >>= 1)
        if (index & 1u) x ^= v[std::size_t(k)];
    return x;
}

}  // namespace iris
