#include "integrators/stokes_throughput.h"

#include "spectral/stokes_basis.h"

namespace iris {

StokesThroughput::StokesThroughput(int rows, int n, const vec3& basis) : rows_(rows), basis_(basis) {
    for (int k = 0; k < rows_; ++k)
        for (int j = 0; j < 4; ++j) r_[k][j] = SampledSpectrum(n, k == j ? 1.0f : 0.0f);
}

void StokesThroughput::changeBasis(const vec3& forward, const vec3& next) {
    // rows · rotator(c, s): columns 1 and 2 become (c r1 − s r2, s r1 + c r2) (Collett ch. 5 eq. 43).
    const mueller::BasisRotation R = stokesBasisRotation(forward, next, basis_);
    basis_ = next;
    if (R.c2 == 1.0f && R.s2 == 0.0f) return;
    const int n = r_[0][0].size();
    for (int k = 0; k < rows_; ++k)  // lane by lane: the spectrum operations' float products, no temporaries
        for (int l = 0; l < n; ++l) {
            const float a = r_[k][1][l], b = r_[k][2][l];
            r_[k][1][l] = a * R.c2 - b * R.s2;
            r_[k][2][l] = a * R.s2 + b * R.c2;
        }
}

void StokesThroughput::apply(const MuellerSpectrum& M, const vec3& inputBasis) {
    basis_ = inputBasis;
    if (M.depolarizing()) {  // only M(0, 0): what remains is the response to unpolarized light
        for (int k = 0; k < rows_; ++k) {
            r_[k][0] *= M(0, 0);
            for (int j = 1; j < 4; ++j) r_[k][j] = SampledSpectrum(r_[k][0].size());
        }
        return;
    }
    // Row times matrix lane by lane, summed over i = 0..3 in order (the spectrum operations' values).
    const int n = r_[0][0].size();
    for (int k = 0; k < rows_; ++k)
        for (int l = 0; l < n; ++l) {
            const float x[4] = {r_[k][0][l], r_[k][1][l], r_[k][2][l], r_[k][3][l]};
            for (int j = 0; j < 4; ++j) {
                float v = x[0] * M(0, j)[l];
                for (int i = 1; i < 4; ++i) v += x[i] * M(i, j)[l];
                r_[k][j][l] = v;
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
    for (int k = 0; k < rows_; ++k)
        for (int j = 0; j < 4; ++j)
            if (r_[k][j].hasNonFinite()) return true;
    return false;
}

}  // namespace iris
