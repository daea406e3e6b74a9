// A polarized path's throughput (docs/polarization.md): instead of Mitsuba 3's 4×4 Mueller
// throughput (src/integrators/path.cpp, throughput · bsdf_weight) the path carries only the rows
// the camera measures — row k maps the Stokes vector of the light arriving along the current
// segment to the measured S_k — so S0 renders multiply 1×4 rows, and the `stokes` integrator 4×4.
// The rows act on Stokes vectors in the reference basis `basis` (world space, orthogonal to the
// segment); a vertex first re-expresses them in the basis its Mueller matrix leaves in, then
// multiplies by the matrix, whose input basis becomes the segment's.
#pragma once

#include "core/math.h"
#include "spectral/mueller.h"

namespace iris {

class StokesThroughput {
public:
    /// Identity rows 0..rows−1 in basis `basis` (orthogonal to the first segment).
    StokesThroughput(int rows, int n, const vec3& basis);

    int rows() const { return rows_; }
    const vec3& basis() const { return basis_; }
    /// Element (k, j) of the rows.
    const SampledSpectrum& at(int k, int j) const { return r_[k][j]; }
    /// The unpolarized part of row 0, r(0, 0): the path weight for unpolarized light, S0's (Mitsuba
    /// 3 unpolarized_spectrum(throughput), used for Russian roulette).
    const SampledSpectrum& intensity() const { return r_[0][0]; }

    /// Re-express the rows for Stokes vectors in basis `next` (orthogonal to `forward`, the
    /// direction the light travels): rows ← rows · R(forward, next → basis) (Mitsuba 3
    /// rotate_stokes_basis).
    void changeBasis(const vec3& forward, const vec3& next);
    /// rows ← rows · M; the rows then act on M's input basis, `inputBasis`.
    void apply(const MuellerSpectrum& M, const vec3& inputBasis);
    void operator*=(float s);
    /// Scales every row by a per-wavelength weight (media's σ and transmittance ratios).
    void operator*=(const SampledSpectrum& s);
    /// The measurement of unpolarized light of radiance L arriving through M (M's output basis
    /// being the rows' basis) with weight w: est.S_k += Σ_j rows(k, j) M(j, 0) L w.
    void addThrough(const MuellerSpectrum& M, const SampledSpectrum& L, float w, StokesVector& est) const;
    /// The measurement of unpolarized light of radiance L arriving along the segment, weight w.
    void addUnpolarized(const SampledSpectrum& L, float w, StokesVector& est) const;
    bool isBlack() const { return r_[0][0].isBlack(); }
    bool hasNonFinite() const;

private:
    int rows_;
    vec3 basis_;
    SampledSpectrum r_[4][4];
};

}  // namespace iris
