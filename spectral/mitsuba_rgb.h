// How Mitsuba's RGB variants turn a tabulated spectrum (a `<spectrum value="λ:v, ...">` or
// `filename=` value, a named conductor's data/ior/*.spd) into the one RGB triple they render with,
// so that iris's RGB mode renders a Mitsuba scene as Mitsuba's RGB variant does (issue 14). The
// rule is the convention of the value (SpectrumValue::convention, or a plugin's `convention`;
// core/mitsuba_convention.h: the upgrade pass gives a version 0.x file's Mitsuba 0.6's rule;
// docs/scene_format.md):
//
//   Mitsuba 3 (2.x/3.x), spectrum_list_to_srgb (src/core/spectrum.cpp): 1000 equally spaced
//     wavelengths w_i = 360 + i·470/999 nm; the spectrum's linear interpolant v(w_i), skipped
//     outside its table; the CIE 1931 curves as Mitsuba tabulates them (5 nm, linear in between);
//       XYZ = (470/1000) · MI_CIE_Y_NORMALIZATION · Σ_i cmf(w_i) v(w_i) [· D65(w_i)/98.9974…]
//     then Mitsuba's XYZ → linear sRGB matrix, clamped to [0, 1] (bounded) or at 0. Which
//     options (include/mitsuba/render/ior.h ior_from_file; src/core/properties.cpp
//     get_texture_impl, older src/core/xml.cpp create_texture_from_spectrum):
//       reflectance             D65 weighted, bounded
//       emitter radiance        not weighted, clamped at 0
//       unbounded (eta, k)      D65 weighted, clamped at 0
//       named conductor         not weighted, clamped at 0
//   Mitsuba 0.6 (0.x), Spectrum::fromContinuousSpectrum (src/libcore/spectrum.cpp): the exact
//     integrals X = ∫ S x̄ dλ / ∫ ȳ dλ over 360–830 nm of the spectrum S (0 outside its table)
//     and the 1 nm CIE curves, never D65 weighted, then the same matrix; a scene's tabulated
//     spectrum first gets InterpolatedSpectrum::zeroExtend (a 0 sample one mean spacing beyond
//     each non-zero end) and is clamped at 0 afterwards (src/librender/scenehandler.cpp); a named
//     conductor's table is used as it is (src/bsdfs/conductor.cpp).
// Spectral mode is not affected: it evaluates the table at the path's wavelengths.
#pragma once

#include <vector>

#include "core/math.h"
#include "core/mitsuba_convention.h"
#include "spectral/spectrum.h"

namespace iris {

/// Mitsuba 3's spectrum_list_to_srgb (see the file comment); lambdas strictly increasing (nm).
vec3 mitsuba3SpectrumToRGB(const std::vector<float>& lambdas, const std::vector<float>& values, bool d65, bool bounded);

/// Mitsuba 0.6's Spectrum::fromContinuousSpectrum of the piecewise-linear table, 0 outside it
/// (RGB build, no clamp).
vec3 mitsuba06SpectrumToRGB(const std::vector<float>& lambdas, const std::vector<float>& values);

/// Mitsuba 0.6's InterpolatedSpectrum::zeroExtend: a 0 sample one mean spacing before the first and
/// after the last sample, where that sample is not 0 (two or more samples).
void mitsuba06ZeroExtend(std::vector<float>& lambdas, std::vector<float>& values);

/// Where a tabulated spectrum comes from: a scene value (`<spectrum>`, `λ:v` or filename) read
/// as `kind`, or the data file of a named conductor (`material`).
enum class MitsubaTableSource { SceneValue, ConductorPreset };

/// The RGB triple the RGB variant of the Mitsuba of `convention` renders the table with.
vec3 mitsubaRGBModeValue(const std::vector<float>& lambdas, const std::vector<float>& values, SpectrumKind kind,
                         MitsubaTableSource source, MitsubaConvention convention);

/// Mitsuba 3's single-valued `<spectrum value="v"/>` of an emitter (src/core/properties.cpp
/// get_texture_impl, older src/core/xml.cpp create_texture_from_spectrum): the flat (equal-energy)
/// spectrum v in spectral mode, its sRGB colour v · M (1, 1, 1) = v · (1.2048, 0.9484, 0.9087) in
/// RGB mode ("this purple-ish color", so that the two variants agree). Mitsuba 0.6 and a `<float>`
/// give v × D65 instead (spectral/spectrum_params.h).
SpectrumPtr mitsuba3UniformEmission(float v);

/// A tabulated spectrum as a Mitsuba plugin reads it: spectral mode evaluates `table` (a
/// PiecewiseLinearSpectrum), RGB mode returns mitsubaRGBModeValue for every kind (also Unbounded,
/// which RGB mode otherwise evaluates at the channel wavelengths). Another spectrum is returned as
/// it is.
SpectrumPtr withMitsubaRGBModeValue(SpectrumPtr table, MitsubaTableSource source, MitsubaConvention convention);

}  // namespace iris
