#include "spectral/cie.h"

#include "spectral/cie_tables.h"
#include "spectral/lane_dispatch.h"

namespace iris::cie {

namespace {
using namespace tables;

// Linear interpolation in a table with samples at first + i*step (nm); 0 outside.
float interpolate(const float* table, int count, float first, float step, float lambda) {
    const float x = (lambda - first) / step;
    if (!(x >= 0.0f) || x > float(count - 1)) return 0.0f;
    const int i = std::min(int(x), count - 2);
    const float t = x - float(i);
    return (1.0f - t) * table[i] + t * table[i + 1];
}

// interpolate() for many wavelengths, in lane loops: the table position of every lane
// (vectorised), the two table reads per lane and table (scalar loads: baseline x86-64 has no
// gather), the blend (vectorised). Each lane does the operations of interpolate() in the same
// order, so the results are identical (d65Lanes; weightedXyzBarSum reads x̄, ȳ, z̄ of one
// position together).
constexpr int kBlock = 32;  // lanes per pass (kMaxWavelengths, spectral/sampled_spectrum.h)

struct TablePositions {
    alignas(16) int index[kBlock];
    alignas(16) float frac[kBlock];
    alignas(16) float inside[kBlock];  // 1 inside the table, 0 outside (interpolate() returns 0)
};

template <int kFirst, int kStep, int kCount>
IRIS_LANES_INLINE void tablePositions(const float* lambda, int m, TablePositions& p) {
    for (int j = 0; j < m; ++j) {
        // As interpolate(): x = (λ − first) / step (the 1 nm tables: λ − first, as in xyzBar).
        const float d = lambda[j] - float(kFirst);
        const float x = kStep == 1 ? d : d / float(kStep);
        const bool in = x >= 0.0f && x <= float(kCount - 1);
        const float xc = in ? x : 0.0f;
        const int i = std::min(int(xc), kCount - 2);
        p.index[j] = i;
        p.frac[j] = xc - float(i);
        p.inside[j] = in ? 1.0f : 0.0f;
    }
}

IRIS_LANES_INLINE void blend(const float* table, int m, const TablePositions& p, float* out) {
    alignas(16) float a[kBlock], b[kBlock];
    for (int j = 0; j < m; ++j) {
        a[j] = table[p.index[j]];
        b[j] = table[p.index[j] + 1];
    }
    for (int j = 0; j < m; ++j) {
        const float t = p.frac[j];
        const float v = (1.0f - t) * a[j] + t * b[j];
        out[j] = p.inside[j] != 0.0f ? v : 0.0f;
    }
}

// x̄, ȳ, z̄ of one 1 nm node as one lane vector (spectral/lanes.h), so that a lane's two nodes are
// two aligned loads and its three blends one vector blend (weightedXyzBarSum). A plain loop over
// the components is vectorised by GCC across wavelengths instead, with emulated gathers, which
// costs more than the scalar code.
using lanes::Float4;
struct CmfRows {
    Float4 row[kCmfCount];  // x̄, ȳ, z̄, 0
    CmfRows() {
        for (int i = 0; i < kCmfCount; ++i) row[i] = Float4{kXBar[i], kYBar[i], kZBar[i], 0.0f};
    }
};
const CmfRows& cmfRows() {
    static const CmfRows rows;  // built on first use (safe from other static initialisers too)
    return rows;
}

double computeYIntegral() {
    double s = 0.0;
    for (int i = 0; i < kCmfCount; ++i) s += kYBar[i];  // × 1 nm
    return s;
}
}  // namespace

float xBar(float lambda) { return interpolate(kXBar, kCmfCount, float(kCmfFirst), 1.0f, lambda); }
float yBar(float lambda) { return interpolate(kYBar, kCmfCount, float(kCmfFirst), 1.0f, lambda); }
float zBar(float lambda) { return interpolate(kZBar, kCmfCount, float(kCmfFirst), 1.0f, lambda); }

vec3 xyzBar(float lambda) {
    const float x = lambda - float(kCmfFirst);
    if (!(x >= 0.0f) || x > float(kCmfCount - 1)) return vec3(0.0f);
    const int i = std::min(int(x), kCmfCount - 2);
    const float t = x - float(i);
    return vec3((1.0f - t) * kXBar[i] + t * kXBar[i + 1], (1.0f - t) * kYBar[i] + t * kYBar[i + 1],
                (1.0f - t) * kZBar[i] + t * kZBar[i + 1]);
}

float d65(float lambda) { return interpolate(kD65, kD65Count, float(kD65First), float(kD65Step), lambda); }

namespace {
IRIS_LANES_INLINE void d65LanesBody(const float* lambda, int count, float* out) {
    TablePositions p;
    if (count == 4) {  // N ≤ 4 (the common case): the same lane operations, with a constant trip count
        tablePositions<kD65First, kD65Step, kD65Count>(lambda, 4, p);
        return blend(kD65, 4, p, out);
    }
    for (int j0 = 0; j0 < count; j0 += kBlock) {
        const int m = std::min(kBlock, count - j0);
        tablePositions<kD65First, kD65Step, kD65Count>(lambda + j0, m, p);
        blend(kD65, m, p, out + j0);
    }
}
IRIS_LANES_KERNEL(void, d65LanesKernel, d65LanesBody, (const float* lambda, int count, float* out), (lambda, count, out))
}  // namespace

void d65Lanes(const float* lambda, int count, float* out) { d65LanesKernel(lanes::useAvx2For(count), lambda, count, out); }

namespace {
// sum += Σ_{j<m} weight[j] · xyzBar(lambda[j]) in j order, for the `padded` (m rounded up to 4,
// at most kBlock) lanes from lambda, weight.
IRIS_LANES_INLINE void addWeightedXyzBar(const float* lambda, const float* weight, int m, int padded, Float4& sum) {
    const CmfRows& rows = cmfRows();
    TablePositions p;
    alignas(16) float oneMinusT[kBlock], wIn[kBlock];
    tablePositions<kCmfFirst, 1, kCmfCount>(lambda, padded, p);
    // The term of xyzBar's plain loop is w · (inside ? v : 0) with v the blend. Here it is
    // (w · inside) · v: for inside = 1 the same product; for inside = 0 both are w · 0 (±0, or
    // NaN for an infinite w), because v is finite and ≥ 0 (at the clamped node 0, t = 0).
    for (int j = 0; j < padded; ++j) {
        oneMinusT[j] = 1.0f - p.frac[j];
        wIn[j] = weight[j] * p.inside[j];
    }
    for (int j = 0; j < m; ++j) {
        const Float4 a = rows.row[p.index[j]];
        const Float4 b = rows.row[p.index[j] + 1];
        // As xyzBar per component, (1 − t)·a + t·b; the scalars are broadcast to all four.
        sum += wIn[j] * (oneMinusT[j] * a + p.frac[j] * b);
    }
}

IRIS_LANES_INLINE vec3 weightedXyzBarSumBody(const float* lambda, const float* weight, int n) {
    Float4 sum = {0.0f, 0.0f, 0.0f, 0.0f};
    if (n <= 4) {  // N ≤ 4 (the common case): the same lane operations, with a constant lane count
        addWeightedXyzBar(lambda, weight, n, 4, sum);
        return vec3(sum[0], sum[1], sum[2]);
    }
    for (int j0 = 0; j0 < n; j0 += kBlock) {
        const int m = std::min(kBlock, n - j0);
        addWeightedXyzBar(lambda + j0, weight + j0, m, (m + 3) & ~3, sum);
    }
    return vec3(sum[0], sum[1], sum[2]);
}
IRIS_LANES_KERNEL(vec3, weightedXyzBarSumKernel, weightedXyzBarSumBody, (const float* lambda, const float* weight, int n),
                  (lambda, weight, n))
}  // namespace

vec3 weightedXyzBarSum(const float* lambda, const float* weight, int n) {
    return weightedXyzBarSumKernel(lanes::useAvx2For(n), lambda, weight, n);
}

double yIntegral() {
    static const double v = computeYIntegral();
    return v;
}

}  // namespace iris::cie
