// Polarized Fresnel terms of one planar interface (polarized mode, docs/polarization.md): the four
// distinct entries A, B, C, D of the interface's Mueller matrix in s-axis bases
// (mueller::interfaceMueller), per wavelength, for the reflection and the refraction of Mitsuba 3's
// conductor, dielectric and their rough versions (include/mitsuba/render/fresnel.h
// fresnel_polarized, mueller.h specular_reflection / specular_transmission).
//
// Amplitudes use iris's convention (docs/thin_film.md §1): time dependence e^{−iωt}, complex index
// ñ = η + iκ, normal wave number q = ñ cos θt = sqrt(ñ² − sin²θi) on the decaying branch Im q ≥ 0,
// and Born & Wolf's r_p (the "Verdet" sign of current Mitsuba 3):
//   r_s = (cos θi − q)/(cos θi + q),   r_p = (ñ² cos θi − q)/(ñ² cos θi + q).
// Mitsuba 3 writes the same amplitudes in the e^{+iωt} convention (κ → −κ, its
// fresnel_polarized), i.e. their complex conjugates, so its a_p a_s* is r_s r_p* here:
//   A = (|r_s|² + |r_p|²)/2,  B = (|r_s|² − |r_p|²)/2,  C + iD = r_s r_p*.
#pragma once

#include "spectral/mueller.h"
#include "spectral/sampled_spectrum.h"

namespace iris {

struct InterfaceMuellerTerms {
    float A = 0, B = 0, C = 0, D = 0;
};

/// Reflection terms at cosThetaI (> 0: from the outside with relative index η + iκ; < 0: from the
/// inside of a dielectric, relative index 1/η; κ must then be 0). κ = 0 and η = 1 give no
/// reflection, as Mitsuba's index-matched case.
InterfaceMuellerTerms reflectionTerms(float cosThetaI, float eta, float k = 0.0f);

/// Transmission terms of a dielectric (real η) for light arriving at cosThetaI (sign as above):
/// T_{s,p} = (η_t cos θt / η_i cos θi)|t_{s,p}|² with t_s = 1 + r_s, t_p = (1 + r_p) η_i/η_t (Born &
/// Wolf §1.5.2); C = √(Ts Tp) (real amplitudes, no phase), D = 0. Zero under total internal
/// reflection (Mitsuba 3 mueller::specular_transmission).
InterfaceMuellerTerms transmissionTerms(float cosThetaI, float eta);

/// A thin dielectric slab (Mitsuba 3 `thindielectric`) per polarization: the incoherent sum of the
/// beams reflected k = 0, 1, 2, ... times inside, whose Mueller matrices add. With the interface's
/// real r_s, r_p (R = r², T = 1 − R, the inside coefficient −r): R' = R + T² R / (1 − R²) =
/// 2R/(1 + R) and T' = (1 − R)/(1 + R) for s and p separately, and the cross terms
/// C_R = r_s r_p (1 + T_s T_p / (1 − R_s R_p)), C_T = T_s T_p / (1 − R_s R_p), D = 0 (the
/// geometric series of (r_s r_p)^{2k−1} and (r_s r_p)^{2k}). Light never reaches the critical angle
/// inside a slab between equal media.
struct SlabMuellerTerms {
    InterfaceMuellerTerms reflection, transmission;
};
SlabMuellerTerms slabTerms(float cosThetaI, float eta);

/// The per-wavelength interface Mueller matrix in s-axis bases from per-lane terms.
template <typename Terms>
MuellerSpectrum interfaceMuellerPerLane(int n, Terms&& terms) {
    SampledSpectrum A(n), B(n), C(n), D(n);
    for (int i = 0; i < n; ++i) {
        const InterfaceMuellerTerms t = terms(i);
        A[i] = t.A, B[i] = t.B, C[i] = t.C, D[i] = t.D;
    }
    return mueller::interfaceMueller(A, B, C, D);
}

}  // namespace iris
