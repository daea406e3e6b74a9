// Sobol direction numbers of the first kSobolDimensions dimensions (Sobol 1967), for the joint
// high-dimensional points of the `highdimsobol` sampler (core/sample_sequences.h).
//
// Dimension 0 is van der Corput's sequence (every m_k = 1, no polynomial). Dimensions 1 .. 31 are
// rows d = 2 .. 32 of Joe & Kuo's table new-joe-kuo-6.21201 (S. Joe and F. Y. Kuo, "Constructing
// Sobol sequences with better two-dimensional projections", SIAM J. Sci. Comput. 30(5), 2008,
// 2635–2654; data from https://web.maths.unsw.edu.au/~fkuo/sobol/): the primitive polynomial
// x^s + a_1 x^(s−1) + … + a_(s−1) x + 1 as its degree s and a = Σ a_k 2^(s−1−k), and the initial
// odd m_1 .. m_s with m_k < 2^k.
#pragma once

#include <array>
#include <cstdint>

namespace iris {

/// How many Sobol dimensions have direction numbers here (joint points beyond them are padded).
constexpr int kSobolDimensions = 32;

/// One row of Joe & Kuo's table: the polynomial's degree s and inner coefficients a, and the
/// initial direction numbers m_1 .. m_s (unused entries 0).
struct SobolPolynomial {
    int degree;
    uint32_t a;
    std::array<uint32_t, 7> m;
};

/// Rows d = 2 .. 32 of new-joe-kuo-6.21201, i.e. dimensions 1 .. kSobolDimensions − 1.
extern const std::array<SobolPolynomial, kSobolDimensions - 1> kJoeKuoRows;

/// v_{d,k} as 32-bit fractions (bit k of the index xors in v_{d,k}): Bratley & Fox, ACM TOMS 14(1),
/// 1988, eq. 2–3, the recurrence m_k = 2a_1 m_{k−1} ⊕ 2²a_2 m_{k−2} ⊕ … ⊕ 2^s m_{k−s} ⊕ m_{k−s}.
extern const std::array<std::array<uint32_t, 32>, kSobolDimensions> kSobolDirections;

/// Bits of the Sobol point of `index` in `dimension` (< kSobolDimensions), as a 32-bit fraction:
/// the xor of v_{d,k} over the set bits k of index (Bratley & Fox 1988, eq. 4, without Gray code).
uint32_t sobolPointBits(uint32_t index, int dimension);

}  // namespace iris
