// Spectrum-valued scene parameters: a float, <rgb>, <spectrum> or <blackbody> value of a
// Properties entry turned into a Spectrum of the kind the plugin asks for (reflectance, unbounded,
// illuminant; spectral/spectrum.h). The typed getters of core/properties.h stop at raw values;
// this is the spectral layer's getter.
#pragma once

#include <string>

#include "core/properties.h"
#include "core/registry.h"
#include "spectral/spectrum.h"

namespace iris {

/// Spectrum plugins, `<spectrum type="regular" name="...">...</spectrum>` (Mitsuba 3's objects:
/// uniform, regular, irregular, blackbody, d65, srgb; spectral/spectrum_plugins.cpp), created for
/// the kind of the parameter they are given to.
using SpectrumRegistry = Registry<const Spectrum, SpectrumKind>;

/// Spectrum from a float, rgb, spectrum or blackbody value or a spectrum plugin object
/// (SpectrumRegistry); a located error when missing or of
/// another type. A plain number given to an emitter (Illuminant kind) is that multiple of D65 with
/// Y = 1, as in Mitsuba 3. A single-valued <spectrum> of an emitter is Mitsuba 3's flat spectrum
/// (mitsuba3UniformEmission, spectral/mitsuba_rgb.h); a version 0.x scene's was made a number
/// (Mitsuba 0.6, intent "illuminant") by the upgrade pass (render/loader/scene_upgrade.h).
SpectrumPtr getSpectrum(const Properties& p, const std::string& name, SpectrumKind kind);
/// As above, `def` (a number, read as above) when absent.
SpectrumPtr getSpectrum(const Properties& p, const std::string& name, SpectrumKind kind, float def);
/// A plain number as a spectrum of the given kind (the rule of getSpectrum for numbers).
SpectrumPtr spectrumFromNumber(float v, SpectrumKind kind);
/// Build a spectrum of the given kind from a <spectrum>/<blackbody> value, with the rules of a
/// version 0.x scene for a single value (a number, see spectrumFromNumber) and the RGB-mode value
/// of spectral/spectrum.h for tables (getSpectrum applies the value's convention).
SpectrumPtr spectrumFromValue(const SpectrumValue& v, SpectrumKind kind, const SourceLocation& loc);
/// The RGB-mode rule of a scene's tabulated reflectance or emission (λ:v pairs, a .spd file, a
/// regular/irregular plugin): rendered with the RGB value the RGB variant of the Mitsuba of
/// `convention` (the value's, or the plugin's `convention` parameter) computes (spectral/mitsuba_rgb.h). Unbounded tables keep the channel-wavelength rule
/// (spectral/spectrum.h) except where a plugin asks for Mitsuba's (conductor eta/k,
/// spectral/ior_params.cpp). Non-tabulated spectra are returned as they are.
SpectrumPtr withSceneTableRGBModeValue(SpectrumPtr spec, SpectrumKind kind, MitsubaConvention convention);

}  // namespace iris
