// Named conductors (Mitsuba 3's `material` values for conductor/roughconductor): measured η and κ
// spectra from the luxpop database (see the headers of spectral/data/ior/*.spd), read with
// loadSpdFile from sourcePath("spectral/data/ior"). "none" is a perfect mirror (F = 1).
#pragma once

#include <string>
#include <vector>

#include "core/properties.h"
#include "spectral/ior.h"
#include "spectral/spectrum.h"

namespace iris {

/// A named conductor's measured tables.
struct ConductorSpectra {
    SpectrumPtr eta, k;  // both null for "none" (perfect mirror)
    bool mirror() const { return !eta; }
};

/// A conductor's complex index η + iκ as a material uses it (two IORs, spectral/ior.h) and the
/// index of the outside medium.
struct ConductorIOR {
    IOR eta, k;
    float extIOR = 1.0f;
    bool mirror = false;  // "none": a perfect mirror, F = 1
    /// η/η_ext and κ/η_ext at the path's wavelengths (zero for the mirror).
    void sample(const SampledWavelengths& wl, SampledSpectrum* etaRel, SampledSpectrum* kRel) const {
        if (mirror) {
            *etaRel = *kRel = SampledSpectrum(wl.size());
            return;
        }
        *etaRel = eta.sample(wl) / extIOR;
        *kRel = k.sample(wl) / extIOR;
    }
};

/// Names Mitsuba 3 lists for conductors, plus "none".
const std::vector<std::string>& conductorPresetNames();
/// Spectra of a named conductor (cached); throws iris::Error for an unknown name.
ConductorSpectra loadConductorPreset(const std::string& name);
/// Folder holding the .spd files.
std::string conductorDataDir();

/// Read a conductor's optical constants from a scene (Mitsuba parameters), with the IOR reader
/// (spectral/ior_params.h):
///   material  preset name when neither eta nor k is given (default "none", Mitsuba 3; a version
///             0.x scene gets Mitsuba 0.6's "Cu" from the upgrade pass, render/loader/scene_upgrade.h)
///   eta, k    IorQuantity::ConductorOptics (float, rgb or spectrum as Mitsuba reads them, ≥ 0) —
///             both or neither
///   ext_ior   float or IOR preset name of the outside medium (iris extension, the thesis uses
///             η_i = 1.00028 for air): default 1 (Mitsuba 3 has no exterior index); in a version
///             0.x scene the upgrade pass gives Mitsuba 0.6's extEta, default 1.000277 ("air")
///   convention "mitsuba3" (default) or "mitsuba0.6": whose RGB value a named conductor's tables
///             render with in RGB mode (spectral/mitsuba_rgb.h); the upgrade pass writes
///             "mitsuba0.6" into a version 0.x scene's conductors (core/mitsuba_convention.h)
ConductorIOR readConductor(const Properties& p);

}  // namespace iris
