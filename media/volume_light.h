// Mitsuba 3's `volumelight` emitter (src/emitters/volumelight.cpp): a medium that emits. It is
// nested in a <medium>, or attached to a shape as its <emitter> and then belongs to the shape's
// interior medium (Mitsuba 3 Medium::set_emitter); a medium has at most one. Its one parameter,
// `radiance` (a number, spectrum, <rgb> or <volume>; default 0), is the radiance the medium adds per
// unit length along a ray: the radiative transfer equation's source term is j(x) itself, not
// pbrt-v4's σ_a·L_e. This is what Mitsuba 3's volpath computes: it adds the emitter's value at
// every collision with a throughput divided by σ_maj (volpath.cpp, get_radiance and
// transmittance_eval_pdf), i.e. ∫ T j dt. An absorbing emitting slab of thickness d and extinction
// σ_t therefore shows j (1 − e^{−σ_t d}) / σ_t, and an infinite scattering one j / σ_a.
// Colours are upsampled as Unbounded values (no D65 factor): Mitsuba 3 reads the parameter with
// Properties::volume, as for any medium quantity, not with the D65 wrapping of surface emitters.
// `to_world` is refused (Mitsuba 3: the light inherits its shape's placement).
#pragma once

#include "core/properties.h"
#include "media/volumes/volume.h"

namespace iris {

/// The emission volume j of a <emitter type="volumelight"> (errors name the emitter's lines).
VolumePtr readVolumeLight(const Properties& emitter);

}  // namespace iris
