// Mueller matrices and Stokes vectors at the N wavelengths of a path (polarized mode,
// docs/polarization.md). Conventions are Mitsuba 3's (include/mitsuba/render/mueller.h): a Stokes
// vector (S0, S1, S2, S3) is meaningful with a reference basis vector x orthogonal to the direction
// the light travels; S1 > 0 is linear polarization along x, S2 > 0 along x rotated by +45° (the
// rotator below), S3 > 0 right circular, the ellipse seen from the sensor looking back along the
// beam (Mitsuba's test_retarder.py: a quarter-wave plate with its fast axis along x turns +45°
// light into S3 = −S0, after Goldstein, "Polarized Light", 3rd ed., eqs. 6.46-6.47). A Mueller
// matrix maps the Stokes vector of the light arriving (in its basis) to that of the light leaving
// (in its basis).
//
// A matrix is 16 SampledSpectrum entries, row-major; `depolarizing` marks the matrices whose only
// non-zero entry is (0, 0) (Mitsuba's depolarizer), which the integrators multiply in one lane op;
// `interfaceLayout` the matrices of mueller::interfaceMueller's layout, whose basis rotation
// (mueller::rotateBases) skips the products with their eight zero entries.
#pragma once

#include <cmath>
#include <new>

#include "spectral/sampled_spectrum.h"

namespace iris {

/// A Stokes vector per wavelength lane.
struct StokesVector {
    SampledSpectrum s[4];
    explicit StokesVector(int n = 0) : s{SampledSpectrum(n), SampledSpectrum(n), SampledSpectrum(n), SampledSpectrum(n)} {}
    /// Unpolarized light of intensity L: (L, 0, 0, 0).
    static StokesVector unpolarized(const SampledSpectrum& L) {
        StokesVector v(L.size());
        v.s[0] = L;
        return v;
    }
};

class MuellerSpectrum {
public:
    explicit MuellerSpectrum(int n = 0) {
        for (SampledSpectrum& e : e_) place(e, n, [](int) { return 0.0f; });
    }
    // Copies touch only the lanes in use, and only entry (0, 0) of a depolarizer: a matrix is
    // 16 × kMaxWavelengths floats, most of it unused at N = 4.
    MuellerSpectrum(const MuellerSpectrum& o) { copyFrom(o); }
    MuellerSpectrum& operator=(const MuellerSpectrum& o) {
        if (this != &o) copyFrom(o);
        return *this;
    }

    int size() const { return e_[0].size(); }
    /// Entry (i, j). A depolarizer stores only (0, 0): read the others after expanded(). A write
    /// access may break the interface layout: it clears interfaceLayout().
    SampledSpectrum& operator()(int i, int j) {
        assert(!depolarizing_ || (i == 0 && j == 0));
        interface_ = false;
        return e_[4 * i + j];
    }
    const SampledSpectrum& operator()(int i, int j) const {
        assert(!depolarizing_ || (i == 0 && j == 0));
        return e_[4 * i + j];
    }
    /// True when only entry (0, 0) may be non-zero (set by depolarizer(); the products keep it).
    bool depolarizing() const { return depolarizing_; }
    /// True when the matrix has the layout [[A, B, 0, 0], [B, A, 0, 0], [0, 0, C, −D], [0, 0, D, C]]
    /// (set by interface(); scaling and sums of two such matrices keep it).
    bool interfaceLayout() const { return interface_; }
    /// The same matrix with all 16 entries stored.
    MuellerSpectrum expanded() const {
        if (!depolarizing_) return *this;
        MuellerSpectrum m(size());
        m.e_[0] = e_[0];
        return m;
    }

    /// Mitsuba 3 mueller::depolarizer: the (0, 0) entry is v, all others 0.
    static MuellerSpectrum depolarizer(const SampledSpectrum& v) {
        MuellerSpectrum m(Uninitialized{});
        m.e_[0] = v;
        m.depolarizing_ = true;
        return m;
    }
    /// The interface layout from its four distinct entries (mueller::interfaceMueller).
    static MuellerSpectrum interface(const SampledSpectrum& A, const SampledSpectrum& B, const SampledSpectrum& C,
                                     const SampledSpectrum& D) {
        MuellerSpectrum m(A.size());  // the zeros; then the eight other entries in place
        const float *a = A.lanes(), *b = B.lanes(), *c = C.lanes(), *d = D.lanes();
        for (int k : {0, 5}) place(m.e_[k], A.size(), [a](int j) { return a[j]; });
        for (int k : {1, 4}) place(m.e_[k], A.size(), [b](int j) { return b[j]; });
        for (int k : {10, 15}) place(m.e_[k], A.size(), [c](int j) { return c[j]; });
        place(m.e_[11], A.size(), [d](int j) { return -d[j]; });
        place(m.e_[14], A.size(), [d](int j) { return d[j]; });
        m.interface_ = true;
        return m;
    }
    /// Mitsuba 3 mueller::absorber: v times the identity (a non-polarizing attenuation).
    static MuellerSpectrum absorber(const SampledSpectrum& v) {
        MuellerSpectrum m(v.size());
        for (int i = 0; i < 4; ++i) m(i, i) = v;
        return m;
    }

    MuellerSpectrum& operator*=(const SampledSpectrum& v) {
        for (int k = 0; k < used(); ++k) e_[k] *= v;
        return *this;
    }
    MuellerSpectrum& operator*=(float v) {
        for (int k = 0; k < used(); ++k) e_[k] *= v;
        return *this;
    }
    MuellerSpectrum& operator+=(const MuellerSpectrum& o) {
        if (depolarizing_ && o.depolarizing_) return e_[0] += o.e_[0], *this;
        if (depolarizing_) *this = expanded();
        if (o.depolarizing_) return e_[0] += o.e_[0], interface_ = false, *this;  // o's other entries are 0
        for (int k = 0; k < 16; ++k) e_[k] += o.e_[k];
        interface_ = interface_ && o.interface_;
        return *this;
    }
    friend MuellerSpectrum operator*(MuellerSpectrum m, const SampledSpectrum& v) { return m *= v; }
    friend MuellerSpectrum operator*(MuellerSpectrum m, float v) { return m *= v; }
    /// Matrix product per lane: (a·b) applies b first, then a.
    friend MuellerSpectrum operator*(const MuellerSpectrum& a, const MuellerSpectrum& b) {
        if (a.depolarizing_ && b.depolarizing_) return depolarizer(a.e_[0] * b.e_[0]);
        const MuellerSpectrum x = a.expanded(), y = b.expanded();
        MuellerSpectrum r(a.size());
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j)
                for (int k = 0; k < 4; ++k) r(i, j) += x(i, k) * y(k, j);
        return r;
    }
    friend StokesVector operator*(const MuellerSpectrum& m, const StokesVector& v) {
        const MuellerSpectrum x = m.expanded();
        StokesVector r(m.size());
        for (int i = 0; i < 4; ++i)
            for (int k = 0; k < 4; ++k) r.s[i] += x(i, k) * v.s[k];
        return r;
    }
    MuellerSpectrum transposed() const {
        if (depolarizing_) return *this;
        MuellerSpectrum r(size());
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j) r(i, j) = (*this)(j, i);
        return r;
    }
    bool hasNonFinite() const {
        for (int k = 0; k < used(); ++k)
            if (e_[k].hasNonFinite()) return true;
        return false;
    }

private:
    struct Uninitialized {};
    explicit MuellerSpectrum(Uninitialized) {}
    int used() const { return depolarizing_ ? 1 : 16; }
    void copyFrom(const MuellerSpectrum& o) {
        depolarizing_ = o.depolarizing_;
        interface_ = o.interface_;
        const int n = o.size();
        for (int k = 0; k < o.used(); ++k) {
            const float* src = o.e_[k].lanes();
            place(e_[k], n, [src](int j) { return src[j]; });
        }
    }
    /// e ← the spectrum of n entries whose lane j is f(j), built in place (an assignment would
    /// build a temporary and copy all kMaxWavelengths lanes of it).
    template <typename F>
    static void place(SampledSpectrum& e, int n, F&& f) {
        ::new (&e) SampledSpectrum(SampledSpectrum::fromLanes(n, f));
    }

    SampledSpectrum e_[16];
    bool depolarizing_ = false;
    bool interface_ = false;
};

/// A real 4×4 matrix applied to every lane (the elementary optical elements below).
struct Mueller4f {
    float m[4][4] = {};
    MuellerSpectrum spectrum(int n) const {
        MuellerSpectrum r(n);
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j)
                if (m[i][j] != 0) r(i, j) = SampledSpectrum(n, m[i][j]);
        return r;
    }
};

namespace mueller {

/// Ideal linear polarizer transmitting linear polarization along the basis vector x (0°), with
/// transmittance `value` for that component (Collett, "Polarized Light", ch. 5 eq. 13; Mitsuba 3
/// mueller::linear_polarizer).
inline Mueller4f linearPolarizer(float value = 1.0f) {
    const float a = 0.5f * value;
    return {{{a, a, 0, 0}, {a, a, 0, 0}, {0, 0, 0, 0}, {0, 0, 0, 0}}};
}

/// Linear retarder with its fast axis along x and phase difference `phase` (radians) between the
/// fast and the slow axis (Goldstein, "Polarized Light", 3rd ed., eq. 6.43; Mitsuba 3
/// mueller::linear_retarder).
inline Mueller4f linearRetarder(float phase) {
    const float s = std::sin(phase), c = std::cos(phase);
    return {{{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, c, s}, {0, 0, -s, c}}};
}

/// Linear diattenuator: field components along 0° and 90° scaled in intensity by x and y
/// (Mitsuba 3 mueller::diattenuator; Chipman, "Polarized Light and Optical Systems", eq. 6.22).
inline Mueller4f diattenuator(float x, float y) {
    const float a = 0.5f * (x + y), b = 0.5f * (x - y), c = std::sqrt(x * y);
    return {{{a, b, 0, 0}, {b, a, 0, 0}, {0, 0, c, 0}, {0, 0, 0, c}}};
}

/// Right and left circular polarizers (Chipman et al., "Polarized Light and Optical Systems",
/// Table 6.2; Mitsuba 3 mueller::right_/left_circular_polarizer).
inline Mueller4f rightCircularPolarizer() {
    return {{{0.5f, 0, 0, 0.5f}, {0, 0, 0, 0}, {0, 0, 0, 0}, {0.5f, 0, 0, 0.5f}}};
}
inline Mueller4f leftCircularPolarizer() {
    return {{{0.5f, 0, 0, -0.5f}, {0, 0, 0, 0}, {0, 0, 0, 0}, {-0.5f, 0, 0, 0.5f}}};
}

/// A rotation of the reference basis, as the pair (cos 2θ, sin 2θ) of the rotation angle θ.
struct BasisRotation {
    float c2 = 1.0f, s2 = 0.0f;
    static BasisRotation ofAngle(float theta) { return {std::cos(2.0f * theta), std::sin(2.0f * theta)}; }
};

/// The rotator: a counter-clockwise rotation of the reference basis by θ seen from the sensor
/// looking back along the beam (Collett ch. 5 eq. 43; Mitsuba 3 mueller::rotator):
/// horizontal light (1, 1, 0, 0) becomes (1, 0, −1, 0) after rotator(45°).
inline Mueller4f rotator(const BasisRotation& r) {
    return {{{1, 0, 0, 0}, {0, r.c2, r.s2, 0}, {0, -r.s2, r.c2, 0}, {0, 0, 0, 1}}};
}

/// An element rotated counter-clockwise by θ about the beam: Rᵀ(θ) M R(θ) (Mitsuba 3
/// mueller::rotated_element; Collett ch. 5 eq. 45).
Mueller4f rotatedElement(float theta, const Mueller4f& m);
Mueller4f multiply(const Mueller4f& a, const Mueller4f& b);

/// R_out · M · R_inᵀ: M re-expressed from new input and output bases (Mitsuba 3
/// mueller::rotate_mueller_basis, with the rotations of rotate_stokes_basis). A matrix with the
/// interface layout takes rotatedInterface, the same operations without the products with zeros.
MuellerSpectrum rotateBases(const MuellerSpectrum& m, const BasisRotation& in, const BasisRotation& out);
/// The dense form of rotateBases for any matrix (what rotatedInterface is tested against).
MuellerSpectrum rotateBasesDense(const MuellerSpectrum& m, const BasisRotation& in, const BasisRotation& out);
/// rotateBases of a matrix with the interface layout (m.interfaceLayout()).
MuellerSpectrum rotatedInterface(const MuellerSpectrum& m, const BasisRotation& in, const BasisRotation& out);

/// The Mueller matrix of a specular interface (reflection or transmission) in the frame whose
/// basis vector x is the s axis (perpendicular to the plane of incidence) on both sides, from
/// A = (Ts + Tp)/2, B = (Ts − Tp)/2 and C + iD = √(Ts Tp) · e^{i(φs − φp)} in iris's e^{−iωt}
/// convention (C + iD = r_s r_p* for a reflection): Mitsuba 3 mueller::specular_reflection with its
/// a_p a_s* = conj(r_p) r_s (its amplitudes use e^{+iωt}, fresnel.h), i.e.
///   [[A, B, 0, 0], [B, A, 0, 0], [0, 0, C, −D], [0, 0, D, C]].
inline MuellerSpectrum interfaceMueller(const SampledSpectrum& A, const SampledSpectrum& B, const SampledSpectrum& C,
                                        const SampledSpectrum& D) {
    return MuellerSpectrum::interface(A, B, C, D);
}

}  // namespace mueller

}  // namespace iris
