// The thin-film models that production formats ship, evaluated as they are written, and the
// conversions they rely on. Every function here returns what its source specifies, approximations
// included: they are the objects of study of experiments/industry_thin_film.py, measured against
// iris's exact per-wavelength interference (spectral/thin_film_stack.h). docs/gltf.md §Thin film.
//
//  * KHR_materials_iridescence (Khronos glTF extension, ratified 2022; README "Iridescence Fresnel",
//    sections "Material Interfaces", "Phase Shift", "Analytic Spectral Integration"): Belcour & Barla
//    2017 with Schlick Fresnel on both interfaces, the base index recovered from F0, phase shifts
//    0 or π by comparing indices, two harmonics and the Gaussian fit of the CIE 1931 functions'
//    Fourier transform, mapped to linear Rec.709 with the sRGB matrix and no white balance.
//  * Gulbrandsen 2014, "Artist Friendly Metallic Fresnel", JCGT 3(4): the complex index (n, k) of a
//    conductor from its normal-incidence reflectivity r and edge tint g.
#pragma once

#include "core/math.h"
#include "spectral/thin_film_stack.h"

namespace iris {

/// Schlick 1994: F = F0 + (1 − F0)(1 − cosθ)⁵ (glTF 2.0 Appendix B.3.4, f90 = 1).
double schlickFresnel(double f0, double cosTheta);

/// Normal-incidence reflectance of an interface between real indices: ((n_t − n_i)/(n_t + n_i))²
/// (KHR_materials_iridescence, "IorToFresnel0").
double iorToFresnel0(double transmittedIor, double incidentIor);

/// The real index whose normal-incidence reflectance against air is f0: (1 + √f0)/(1 − √f0)
/// (KHR_materials_iridescence, "Fresnel0ToIor"; f0 must be < 1).
double fresnel0ToIor(double f0);

/// KHR_materials_iridescence's sensitivity S(OPD, shift) per Rec.709 channel: the Gaussian fit of
/// the Fourier transform of the CIE 1931 x̄, ȳ, z̄ at phase 2π·OPD·1e−9 (OPD in nm), divided by
/// 1.0685e−7 and mapped with XYZ_TO_REC709 (README, "evalSensitivity").
dvec3 khrSensitivity(double opdNm, const dvec3& shift);

/// KHR_materials_iridescence's iridescent_fresnel(outsideIor, iridescenceIor, baseF0, thickness,
/// cosθ1) exactly as the README's "Iridescence Fresnel" section writes it: linear Rec.709 RGB.
/// One guard is added: F0 + 0.0001 (the README's) is capped at 0.9999 (F0 ≥ 0.9999 divides by zero).
dvec3 khrIridescentFresnel(double outsideIor, double filmIor, const dvec3& baseF0, double thicknessNm, double cosTheta1);

/// Gulbrandsen 2014 (JCGT 3(4), §3): n = g·n_min(r) + (1 − g)·n_max(r) with n_min = (1 − r)/(1 + r),
/// n_max = (1 + √r)/(1 − √r), and k = √((r (n + 1)² − (n − 1)²)/(1 − r)). r is clamped to
/// [0, 0.99], g to [0, 1]; the result reflects exactly r at normal incidence against air.
complexd gulbrandsenIor(double r, double g);

/// The exact unpolarised reflectance of one film (real index filmIor, thickness in nm) in an
/// exterior of real index outsideIor over a substrate of complex index, at one wavelength
/// (Airy sum, spectral/thin_film_stack.h). d = 0 gives the bare substrate's Fresnel reflectance.
double exactThinFilmReflectance(double lambdaNm, double cosTheta1, double outsideIor, double filmIor, double thicknessNm,
                                complexd substrate);

}  // namespace iris
