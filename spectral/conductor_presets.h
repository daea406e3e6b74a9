// Named conductors (Mitsuba 3's `material` values for conductor/roughconductor): measured η and κ
// spectra from the luxpop database (see the headers of spectral/data/ior/*.spd), read with
// loadSpdFile from sourcePath("spectral/data/ior"). "none" is a perfect mirror (F = 1).
#pragma once

#include <string>
#include <vector>

#include "core/properties.h"
#include "spectral/spectrum.h"

namespace iris {

struct ConductorSpectra {
    SpectrumPtr eta, k;  // both null for "none" (perfect mirror)
    float extIOR = 1.0f; // index of the outside medium (η and κ are divided by it)
    bool mirror() const { return !eta; }
};

/// Names Mitsuba 3 lists for conductors, plus "none".
const std::vector<std::string>& conductorPresetNames();
/// Spectra of a named conductor (cached); throws iris::Error for an unknown name.
ConductorSpectra loadConductorPreset(const std::string& name);
/// Folder holding the .spd files.
std::string conductorDataDir();

/// Read a conductor's optical constants from a scene (Mitsuba parameters):
///   material  preset name (default "none" when neither eta nor k is given)
///   eta, k    spectra (float, rgb, spectrum; Unbounded kind) — both or neither
///   ext_ior   float or IOR preset name of the outside medium (default 1; iris extension, the
///             thesis uses η_i = 1.00028 for air)
ConductorSpectra readConductor(const Properties& p);

}  // namespace iris
