// Belcour & Barla 2017, "A Practical Extension to Microfacet Theory for the Modeling of Varying
// Iridescence", ACM TOG 36(4):65 — the spectrally integrated (CIE-weighted) RGB reflectance of a
// dielectric thin film over a dielectric or conducting base, used by the thin-film materials in
// RGB mode with rgb_mode = "belcour_barla" (docs/thin_film.md §Belcour–Barla).
//
// Airy reflectance of one polarisation as a Fourier series in the phase ψ = 2π·OPD/λ + φ
// (the paper's reformulation of Airy summation for the spectral integration; equation numbers are
// not quoted here, only the published quantities):
//   R(λ) = C0 + 2 Σ_{m≥1} Cm cos(m ψ),   OPD = 2 η2 d cosθ2,  φ = φ21 + φ23,
//   C0 = R12 + Rs,  Cm = (Rs − T121) r123^m,  Rs = T121² R23 / (1 − R123),  r123 = sqrt(R12 R23),
// with R12 = |r12|², T121 = 1 − R12, R23 = |r23|², φ21 = arg(r21) = arg(−r12), φ23 = arg(r23).
// The spectral integral against a sensitivity s(λ) replaces cos(m ψ) by
//   S(m·OPD, m·φ) = ∫ cos(2π m OPD/λ + m φ) s(λ) dλ / ∫ s(λ) dλ   (the paper's spectral integration),
// evaluated with the paper's Gaussian fit of the Fourier transform of the CIE 1931 x̄, ȳ, z̄
// (supplemental material; constants as published, also in the Khronos glTF
// KHR_materials_iridescence specification, "Analytic spectral integration").
#pragma once

#include "core/math.h"
#include "spectral/thin_film_stack.h"

namespace iris {

/// Per-channel (linear Rec.709) sensitivity S_c(OPD, shift), normalised so that S_c(0, 0) = 1:
/// the XYZ Gaussian fit mapped to Rec.709 and divided channel-wise by the mapped white (equal-energy
/// illuminant), so a spectrally constant reflectance stays the same value in every channel.
dvec3 belcourBarlaSensitivity(double opdNm, double shift);

/// Fourier coefficients of the Airy reflectance of one polarisation (see the file comment).
struct AiryFourier {
    double C0 = 1, Rs = 0, T121 = 0, r123 = 0;  // Cm = (Rs − T121) r123^m
    double opdNm = 0, phi = 0;
    bool totalReflection = false;
};
/// pol = 0: s, 1: p. Film must be non-absorbing (its k is ignored); eta1 is the exterior index.
AiryFourier airyFourier(int pol, double cosTheta1, double eta1, double filmEta, double filmThicknessNm,
                        complexd substrate);
/// The series evaluated at one wavelength with `terms` harmonics (exact Airy as terms → ∞).
double airyFourierAt(const AiryFourier& f, double lambdaNm, int terms);

/// Spectrally integrated unpolarised reflectance for RGB channel c ∈ {0,1,2}, with the indices of
/// that channel. Harmonics are summed until r123^m < 1e-5 or the fit's Gaussian envelope at m·OPD
/// is below 1e-8 (the paper keeps m ≤ 2). In [0, 1].
double belcourBarlaReflectance(int c, double cosTheta1, double eta1, double filmEta, double filmThicknessNm,
                               complexd substrate);

}  // namespace iris
