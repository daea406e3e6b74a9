// The one reader of index-of-refraction parameters, for every material (docs/materials.md,
// "Indices of refraction"). A parameter `name` is given as
//   float            a constant
//   string           a preset name (spectral/ior_presets.h, e.g. "bk7", "water") or a number as text
//   rgb (or vector)  per-channel values at the channel wavelengths: `<name>_wavelengths` (vector, nm;
//                    default defaultChannelWavelengths()), or the material's own (granier/proposed
//                    `wavelengths`)
//   spectrum         tabulated (a constant spectrum is a constant)
// or, instead of `name`, by a dispersion formula named after its base B (the name without a
// trailing "_ior": int_ior → int, film_ior → film, eta_t → eta_t):
//   B_cauchy_a, B_cauchy_b          Cauchy A and B (µm²) as floats (B defaults to 0)
//   B_sellmeier_b, B_sellmeier_c    Sellmeier B1..3 and C1..3 (µm²) as vectors
// Which forms a parameter takes and its valid range follow its IorQuantity. Every value read is
// checked at load time (finite, and > 0 or ≥ 0 at every wavelength): a located error otherwise.
#pragma once

#include <string>

#include "core/properties.h"
#include "spectral/ior.h"

namespace iris {

enum class IorQuantity {
    /// A real index η > 0 (dielectrics, films, layers, substrates, the thesis' η_t): every form.
    Index,
    /// An extinction coefficient κ ≥ 0 (film_k, layerN_k, substrate_k): float, rgb, spectrum.
    Extinction,
    /// Mitsuba's conductor `eta` and `k` (≥ 0; measured tables have zeros): float, spectrum, and an
    /// rgb read as Mitsuba 3's conductor plugin reads it, an upsampled unbounded spectrum
    /// (spectral/rgb_spectrum.h), not the per-channel form.
    ConductorOptics,
};

/// Read IOR parameter `name` (e.g. "int_ior", "film_k") in any form its quantity accepts; `def`
/// when no form is given.
IOR readIOR(const Properties& p, const std::string& name, const IOR& def, IorQuantity quantity = IorQuantity::Index);
/// The same for an index whose rgb form stands at channel wavelengths the material fixes (the
/// thesis models' `wavelengths`) instead of `<name>_wavelengths`.
IOR readIOR(const Properties& p, const std::string& name, const IOR& def, const vec3& channelLambdas);
/// A non-dispersive index (a float, a preset name, three equal rgb values, ...), `def` when
/// absent; a located error for a dispersive one.
float readConstantIOR(const Properties& p, const std::string& name, float def);
/// A dielectric interface's `int_ior` and `ext_ior`, with the defaults of Mitsuba 3's dielectric
/// plugins ("bk7" and "air"; src/bsdfs/dielectric.cpp).
struct InterfaceIOR {
    IOR in, ext;
};
InterfaceIOR readInterfaceIOR(const Properties& p);
/// True when `name` or one of its dispersion-formula parameters is given.
bool iorGiven(const Properties& p, const std::string& name);

}  // namespace iris
