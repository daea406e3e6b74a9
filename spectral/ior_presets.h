// Named dielectric indices: Mitsuba 3's table of IOR presets, so that `int_ior`, `ext_ior`,
// `film_ior`, `eta_t`, ... may be given as names (`<string name="int_ior" value="bk7"/>`).
#pragma once

#include <string>
#include <vector>

#include "spectral/ior.h"

namespace iris {

/// The index of a named material (case-insensitive, as Mitsuba 3's lookup_ior); false for an
/// unknown name.
bool lookupIORPreset(const std::string& name, float* eta);
/// All preset names, in the table's order (for error messages and docs).
std::vector<std::string> iorPresetNames();
/// "vacuum, helium, ..." (the list an unknown name's error message gives).
std::string iorPresetList();
/// The preset as a constant IOR; throws iris::Error for an unknown name (for built-in defaults).
IOR presetIOR(const std::string& name);

}  // namespace iris
