// Blender Cycles 4.2's thin film (the Principled BSDF's "Thin Film" inputs), evaluated as its
// source writes it: the object of study of experiments/industry_thin_film.py, measured against
// iris's exact per-wavelength interference. docs/gltf.md §Thin film.
//
// Source, read to learn the method (no code copied): Blender commit 17f2cdd1 "Cycles: Add thin
// film iridescence to Principled BSDF" (pull request projects.blender.org/blender/blender/pulls/
// 118477, merged 2024-05-02, shipped in Blender 4.2 LTS), intern/cycles/kernel/closure/bsdf_util.h:
// fresnel_dielectric_polarized, iridescence_lookup_sensitivity, iridescence_airy_summation,
// fresnel_iridescence; intern/cycles/scene/shader.cpp, ShaderManager::init_xyz_transforms
// (white_xyz and the XYZ → Rec.709 fallback matrix); intern/cycles/kernel/svm/types.h
// THINFILM_THICKNESS_CUTOFF (the Principled BSDF evaluates the film only above 0.1 nm).
// The method is Belcour & Barla 2017 ("A Practical Extension to Microfacet Theory for the Modeling
// of Varying Iridescence", ACM TOG 36(4):65) with:
//  * exact polarised dielectric Fresnel at both interfaces, phase shifts 0 or π from the signs of
//    the amplitudes;
//  * the film index blended towards the outside index below 30 nm (smoothstep);
//  * harmonics m = 1, 2, 3 only, each weighted by the paper's Gaussian fit of the Fourier transform
//    of the CIE 1931 x̄, ȳ, z̄ (the reference implementation's constants, in XYZ);
//  * the XYZ result multiplied channel-wise by the working space's white (XYZ of RGB (1, 1, 1)),
//    mapped to RGB and clamped to [0, 1].
// Dielectric bases only (the commit leaves films on metals for later). Later Cycles releases
// replaced the Gaussian fit by a precomputed table (commit eaa5f63, "Replace thin-film basis
// function approximation with accurate LUTs") and added conductors; that is not this reading.
#pragma once

#include "core/math.h"

namespace iris {

/// Cycles' THINFILM_THICKNESS_CUTOFF (kernel/svm/types.h): at or below 0.1 nm the Principled BSDF
/// uses the plain dielectric Fresnel term.
inline constexpr double kCyclesThinFilmCutoffNm = 0.1;

/// Cycles' smoothstep (util/math): 0 below e0, 1 from e1 on, else (3 − 2t)t² with t = (x − e0)/(e1 − e0).
double cyclesSmoothstep(double e0, double e1, double x);

/// fresnel_iridescence's film index: below 30 nm mix(η1, η2, smoothstep(0, 30, d)), else η2.
double cyclesFilmIndex(double outsideIor, double filmIor, double thicknessNm);

/// fresnel_dielectric_polarized(cosθi, η): s and p power reflectances, the phase shifts π where the
/// amplitude is negative (r_s = (cosθi − η cosθt)/(cosθi + η cosθt), r_p = (η cosθi − cosθt)/(η cosθi + cosθt)),
/// and |cosθt|. Total internal reflection: R = 1, phases 0, tir = true.
struct CyclesPolarizedFresnel {
    double Rs = 1, Rp = 1, phiS = 0, phiP = 0, cosT = 0;
    bool tir = true;
};
CyclesPolarizedFresnel cyclesFresnelDielectricPolarized(double cosThetaI, double eta);

/// iridescence_lookup_sensitivity: the Gaussian fit in XYZ at phase 2π·OPD·1e−9 (OPD in nm),
/// divided by 1.0685e−7; S(0, 0) ≈ (1, 1, 1).
dvec3 cyclesSensitivityXYZ(double opdNm, double shift);

/// iridescence_airy_summation for one polarisation, in XYZ: (R12 + Rs)·(1, 1, 1) plus
/// 2 Cm S(m·OPD, m·φ) for m = 1, 2, 3, Cm = (Rs − T121) r123^m, Rs = T121² R23 / (1 − R12 R23);
/// (1, 1, 1) when R23 = 1.
dvec3 cyclesAirySummationXYZ(double T121, double R12, double R23, double opdNm, double phi);

/// fresnel_iridescence before the colour conversion: the polarisation average of the Airy sums in
/// XYZ for outside, film and base indices η1, η2, η3 (no 30 nm blend, see cyclesThinFilmRGB);
/// (1, 1, 1) on total internal reflection at either interface.
dvec3 cyclesFresnelIridescenceXYZ(double eta1, double eta2, double eta3, double cosTheta1, double thicknessNm);

/// Cycles' XYZ → linear Rec.709 matrix (shader.cpp, init_xyz_transforms, the Rec.709 default that
/// Blender's standard OpenColorIO configuration reproduces), and its white: XYZ of RGB (1, 1, 1).
dvec3 cyclesXyzToRec709(const dvec3& xyz);
const dvec3& cyclesRec709WhiteXYZ();

/// The reading: Cycles 4.2's film Fresnel in linear Rec.709 for a film of index filmIor and
/// thickness d (nm) between an outside and a dielectric base of real indices, at cosθ1 (the
/// microfacet's |ω·h|). d ≤ kCyclesThinFilmCutoffNm: the unpolarised dielectric Fresnel of the
/// base (grey); else saturate(M · (white ⊙ XYZ)) with the film index cyclesFilmIndex.
dvec3 cyclesThinFilmRGB(double outsideIor, double filmIor, double baseIor, double cosTheta1, double thicknessNm);

}  // namespace iris
