// The lane type (spectral/lanes.h) operation by operation against the scalar operation it stands
// for, bit for bit, in both builds of spectral/lane_dispatch.h (the AVX2 one where the CPU has
// AVX2), on random values of every magnitude and on the special values (±0, ±∞, NaN, subnormals).
#include <gtest/gtest.h>

// laneOpsBody passes Double4 between always-inline functions only (spectral/lanes.h).
#pragma GCC diagnostic ignored "-Wpsabi"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <vector>

#include "core/rng.h"
#include "spectral/lane_dispatch.h"

using namespace iris;

namespace {

// The operations under test, in the order of the output rows.
enum Op { kAdd, kSub, kMul, kDiv, kSqrt, kMin, kMax, kClamp, kAbs, kCopysign, kSelect, kOps };
const char* const kOpNames[kOps] = {"+", "-", "*", "/", "sqrt", "min", "max", "clamp", "abs", "copysign", "select"};

// Row op of out (n values each): the lane operation on lanes a[j], b[j] (j in groups of 4).
// clamp puts a into [min(b, −b), max(b, −b)] (= [−|b|, |b|]); select picks a
// where a < b, else b (a min that is not std::min on NaN); bits (per group) goes to mask[j/4].
template <typename T, typename V>
IRIS_LANES_INLINE void laneOpsBody(const T* a, const T* b, int n, T* out, int* mask) {
    for (int j = 0; j < n; j += 4) {
        const V x = lanes::load(a + j), y = lanes::load(b + j);
        const V lo = lanes::min(y, -y), hi = lanes::max(y, -y);
        const V r[kOps] = {x + y,
                           x - y,
                           x * y,
                           x / y,
                           lanes::sqrt(x),
                           lanes::min(x, y),
                           lanes::max(x, y),
                           lanes::clamp(x, lo, hi),
                           lanes::abs(x),
                           lanes::copysign(x, y),
                           lanes::select<V>(x < y, x, y)};
        for (int k = 0; k < kOps; ++k) lanes::store(out + size_t(k) * size_t(n) + size_t(j), r[k]);
        mask[j / 4] = lanes::bits(x < y);
    }
}
IRIS_LANES_INLINE void floatOpsBody(const float* a, const float* b, int n, float* out, int* mask) {
    laneOpsBody<float, lanes::Float4>(a, b, n, out, mask);
}
IRIS_LANES_INLINE void doubleOpsBody(const double* a, const double* b, int n, double* out, int* mask) {
    laneOpsBody<double, lanes::Double4>(a, b, n, out, mask);
}
// int(x) and float(i) per lane.
IRIS_LANES_INLINE void convertBody(const float* x, int n, int32_t* i, float* back) {
    for (int j = 0; j < n; j += 4) {
        const lanes::Int4 v = lanes::toInt(lanes::load(x + j));
        lanes::store(i + j, v);
        lanes::store(back + j, lanes::toFloat(v));
    }
}
IRIS_LANES_KERNEL(void, floatOps, floatOpsBody, (const float* a, const float* b, int n, float* out, int* mask),
                  (a, b, n, out, mask))
IRIS_LANES_KERNEL(void, doubleOps, doubleOpsBody, (const double* a, const double* b, int n, double* out, int* mask),
                  (a, b, n, out, mask))
IRIS_LANES_KERNEL(void, convert, convertBody, (const float* x, int n, int32_t* i, float* back), (x, n, i, back))

/// The scalar operation op on (x, y), the reference of the lane row.
template <typename T>
T scalarOp(int op, T x, T y) {
    switch (op) {
        case kAdd: return x + y;
        case kSub: return x - y;
        case kMul: return x * y;
        case kDiv: return x / y;
        case kSqrt: return std::sqrt(x);
        case kMin: return std::min(x, y);
        case kMax: return std::max(x, y);
        case kClamp: return std::clamp(x, std::min(y, -y), std::max(y, -y));
        case kAbs: return std::fabs(x);
        case kCopysign: return std::copysign(x, y);
        default: return x < y ? x : y;
    }
}

/// Equal bit patterns, or both NaN (the sign and payload of a NaN result are not specified by
/// IEEE 754 for sqrt of a negative number, and differ between x87/SSE/libm).
template <typename T>
bool sameValue(T a, T b) {
    if (std::isnan(a) && std::isnan(b)) return true;
    if constexpr (sizeof(T) == 4)
        return std::bit_cast<uint32_t>(a) == std::bit_cast<uint32_t>(b);
    else
        return std::bit_cast<uint64_t>(a) == std::bit_cast<uint64_t>(b);
}

/// Index of the first lane of row `op` of `out` that differs from scalarOp, or −1.
template <typename T, typename Scalar>
long firstMismatch(const std::vector<T>& a, const std::vector<T>& b, const T* row, Scalar scalar) {
    for (size_t j = 0; j < a.size(); ++j)
        if (!sameValue(row[j], scalar(a[j], b[j]))) return long(j);
    return -1;
}

/// Inputs: every pair of special values, then random values log-uniform over the whole range,
/// both signs (n a multiple of 4).
template <typename T>
void makeInputs(std::vector<T>& a, std::vector<T>& b) {
    using L = std::numeric_limits<T>;
    const T special[] = {T(0), -T(0), T(1), T(-1), L::infinity(), -L::infinity(), L::quiet_NaN(),
                         L::denorm_min(), -L::denorm_min(), L::min(), L::max(), T(0.5), T(3)};
    for (T x : special)
        for (T y : special) {
            a.push_back(x);
            b.push_back(y);
        }
    Pcg32 rng(2024, 13);
    const double e = std::log2(double(L::max())) - 1;
    while (a.size() % 4 != 0 || a.size() < 20000) {
        for (std::vector<T>* v : {&a, &b}) {
            const double m = std::exp2((2.0 * rng.uniform() - 1.0) * e) * (1.0 + rng.uniform());
            v->push_back(T(rng.uniform() < 0.5 ? -m : m));
        }
    }
}

/// Both builds (the AVX2 one only where the CPU has it).
std::vector<bool> builds() {
    std::printf("AVX2 build %s on this CPU\n", lanes::useAvx2() ? "available: both builds tested" : "not available");
    if (lanes::useAvx2()) return {false, true};
    return {false};
}

template <typename T, typename Kernel>
void checkEveryOperation(Kernel kernel) {
    std::vector<T> a, b;
    makeInputs(a, b);
    const int n = int(a.size());
    for (bool avx2 : builds()) {
        std::vector<T> out(size_t(kOps) * size_t(n));
        std::vector<int> mask(size_t(n / 4));
        kernel(avx2, a.data(), b.data(), n, out.data(), mask.data());
        for (int op = 0; op < kOps; ++op) {
            const long j = firstMismatch(a, b, out.data() + size_t(op) * size_t(n),
                                         [op](T x, T y) { return scalarOp(op, x, y); });
            EXPECT_EQ(j, -1) << (avx2 ? "AVX2" : "baseline") << " build, " << kOpNames[op] << " of (" << a[size_t(j)]
                             << ", " << b[size_t(j)] << ")";
        }
        for (int g = 0; g < n / 4; ++g) {
            int want = 0;
            for (int k = 0; k < 4; ++k) want |= (a[size_t(4 * g + k)] < b[size_t(4 * g + k)]) << k;
            ASSERT_EQ(mask[size_t(g)], want) << (avx2 ? "AVX2" : "baseline") << " build, bits of group " << g;
        }
    }
}

}  // namespace

TEST(Lanes, FloatOperationsEqualTheScalarOperations) { checkEveryOperation<float>(floatOps); }

TEST(Lanes, DoubleOperationsEqualTheScalarOperations) { checkEveryOperation<double>(doubleOps); }

TEST(Lanes, IntegerConversionTruncatesAsTheScalarCast) {
    std::vector<float> x = {0.0f, -0.0f, 0.99999994f, 1.0f, -1.5f, 2.5f, 23.999998f, -7.0f, 8388607.5f, 2.1e9f, -2.1e9f, 1e-30f};
    Pcg32 rng(7, 3);
    while (x.size() < 4000) x.push_back((2.0f * rng.uniform() - 1.0f) * 1e6f);
    const int n = int(x.size());
    for (bool avx2 : builds()) {
        std::vector<int32_t> i(size_t(n), 0);
        std::vector<float> back(size_t(n), 0.0f);
        convert(avx2, x.data(), n, i.data(), back.data());
        for (int j = 0; j < n; ++j) {
            ASSERT_EQ(i[size_t(j)], int32_t(x[size_t(j)])) << x[size_t(j)];
            ASSERT_EQ(back[size_t(j)], float(int32_t(x[size_t(j)]))) << x[size_t(j)];
        }
    }
}

TEST(Lanes, TheCheckRejectsAnOperationWithOtherNanOrZeroSemantics) {
    // The comparison above is bit-exact: a lane "min" written a < b ? a : b (not std::min's
    // b < a ? b : a) differs from std::min on (NaN, 1) and (+0, −0), and the check finds it.
    const std::vector<float> a = {1.0f, 2.0f, std::numeric_limits<float>::quiet_NaN(), 0.0f};
    const std::vector<float> b = {3.0f, 1.0f, 1.0f, -0.0f};
    std::vector<float> wrong(4);
    for (int j = 0; j < 4; ++j) wrong[size_t(j)] = a[size_t(j)] < b[size_t(j)] ? a[size_t(j)] : b[size_t(j)];
    EXPECT_EQ(firstMismatch(a, b, wrong.data(), [](float x, float y) { return std::min(x, y); }), 2);
    // ... and the right one passes.
    std::vector<float> out(size_t(kOps) * 4);
    int mask[1];
    floatOps(false, a.data(), b.data(), 4, out.data(), mask);
    EXPECT_EQ(firstMismatch(a, b, out.data() + size_t(kMin) * 4, [](float x, float y) { return std::min(x, y); }), -1);
}

TEST(Lanes, FloatDoubleConversionsEqualTheScalarCasts) {
    // toFloat(Double4) rounds as float(double) (to nearest; overflow to ±∞, NaN stays NaN), and
    // toDouble(Float4) is exact; a truncating conversion would differ on the random values.
    std::vector<double> x = {0.0, -0.0, 1.0 + 1e-9, 3.4e38, 3.5e38, -1e-46, 1e-300,
                             std::numeric_limits<double>::infinity(), std::numeric_limits<double>::quiet_NaN()};
    Pcg32 rng(9, 1);
    while (x.size() % 4 != 0 || x.size() < 4000) x.push_back((2.0 * rng.uniform() - 1.0) * std::pow(10.0, 60 * rng.uniform() - 30));
    bool truncationAgrees = true;
    for (size_t j = 0; j < x.size(); j += 4) {
        const lanes::Float4 f = lanes::toFloat(lanes::load(x.data() + j));
        const lanes::Double4 back = lanes::toDouble(f);
        for (int k = 0; k < 4; ++k) {
            const double v = x[j + size_t(k)];
            ASSERT_EQ(std::bit_cast<uint32_t>(f[k]), std::bit_cast<uint32_t>(float(v))) << v;
            ASSERT_EQ(std::bit_cast<uint64_t>(back[k]), std::bit_cast<uint64_t>(double(float(v)))) << v;
            // A conversion rounding toward zero instead (the wrong rule the check must reject).
            const float r = float(v), truncated = std::abs(double(r)) > std::abs(v) ? std::nextafter(r, 0.0f) : r;
            truncationAgrees = truncationAgrees && (std::isnan(v) || truncated == f[k]);
        }
    }
    EXPECT_FALSE(truncationAgrees);
}
