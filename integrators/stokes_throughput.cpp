#include "integrators/stokes_throughput.h"

#include <limits>
#include <new>

#include "spectral/spectrum_lanes.h"
#include "spectral/stokes_basis.h"

namespace iris {

using lanes::Float4;

namespace {

constexpr int kGroup = SampledSpectrum::kLanes;  // lanes per Float4

using lanes::loadGroup;
using lanes::storeGroup;

}  // namespace

StokesThroughput::StokesThroughput(int rows, int n, const vec3& basis) : rows_(rows), basis_(basis) {
    for (int k = 0; k < rows_; ++k)
        for (int j = 0; j < 4; ++j) ::new (&r_[k][j]) SampledSpectrum(n, k == j ? 1.0f : 0.0f);  // in place
}

void StokesThroughput::changeBasis(const vec3& forward, const vec3& next) {
    // rows · rotator(c, s): columns 1 and 2 become (c r1 − s r2, s r1 + c r2) (Collett ch. 5 eq. 43).
    const mueller::BasisRotation R = stokesBasisRotation(forward, next, basis_);
    basis_ = next;
    if (R.c2 == 1.0f && R.s2 == 0.0f) return;
    const int padded = r_[0][0].padded();
    const Float4 c = lanes::broadcast(R.c2), s = lanes::broadcast(R.s2);
    for (int k = 0; k < rows_; ++k)  // four lanes at a time: the spectrum operations' float products, no temporaries
        for (int l = 0; l < padded; l += kGroup) {
            const Float4 a = loadGroup(r_[k][1], l), b = loadGroup(r_[k][2], l);
            storeGroup(r_[k][1], l, a * c - b * s);
            storeGroup(r_[k][2], l, a * s + b * c);
        }
}

void StokesThroughput::apply(const MuellerSpectrum& M, const vec3& inputBasis) {
    basis_ = inputBasis;
    const int padded = r_[0][0].padded();
    if (M.depolarizing()) {  // only M(0, 0): what remains is the response to unpolarized light
        for (int k = 0; k < rows_; ++k) {
            r_[k][0] *= M(0, 0);
            for (int j = 1; j < 4; ++j)
                for (int l = 0; l < padded; l += kGroup) storeGroup(r_[k][j], l, Float4{});
        }
        return;
    }
    // Row times matrix four lanes at a time, summed over i = 0..3 in order (the spectrum operations' values).
    for (int k = 0; k < rows_; ++k)
        for (int l = 0; l < padded; l += kGroup) {
            const Float4 x[4] = {loadGroup(r_[k][0], l), loadGroup(r_[k][1], l), loadGroup(r_[k][2], l), loadGroup(r_[k][3], l)};
            for (int j = 0; j < 4; ++j) {
                Float4 v = x[0] * loadGroup(M(0, j), l);
                for (int i = 1; i < 4; ++i) v += x[i] * loadGroup(M(i, j), l);
                storeGroup(r_[k][j], l, v);
            }
        }
}

void StokesThroughput::operator*=(float s) {
    for (int k = 0; k < rows_; ++k)
        for (int j = 0; j < 4; ++j) r_[k][j] *= s;
}

void StokesThroughput::operator*=(const SampledSpectrum& s) {
    for (int k = 0; k < rows_; ++k)
        for (int j = 0; j < 4; ++j) r_[k][j] *= s;
}

void StokesThroughput::addThrough(const MuellerSpectrum& M, const SampledSpectrum& L, float w, StokesVector& est) const {
    const SampledSpectrum Lw = L * w;
    for (int k = 0; k < rows_; ++k) {
        SampledSpectrum c = r_[k][0] * M(0, 0);
        if (!M.depolarizing())
            for (int j = 1; j < 4; ++j) c += r_[k][j] * M(j, 0);
        est.s[k] += c * Lw;
    }
}

void StokesThroughput::addUnpolarized(const SampledSpectrum& L, float w, StokesVector& est) const {
    const SampledSpectrum Lw = L * w;
    for (int k = 0; k < rows_; ++k) est.s[k] += r_[k][0] * Lw;
}

bool StokesThroughput::hasNonFinite() const {
    // Four lanes at a time: |x| < ∞ is false exactly for ±∞ and NaN (std::isfinite); lanes ≥ n are not tested.
    const int n = r_[0][0].size();
    const Float4 inf = lanes::broadcast(std::numeric_limits<float>::infinity());
    lanes::Int4 bad{};
    for (int l = 0; l < r_[0][0].padded(); l += kGroup) {
        const lanes::Int4 inRange = lanes::entryLanes(l, n);
        for (int k = 0; k < rows_; ++k)
            for (int j = 0; j < 4; ++j) bad |= inRange & ~(lanes::abs(loadGroup(r_[k][j], l)) < inf);
    }
    return lanes::bits(bad) != 0;
}

}  // namespace iris
