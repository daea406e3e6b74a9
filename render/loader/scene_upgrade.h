// The one pass between parsing and building (Mitsuba 3's model: src/core/xml.cpp, upgrade_tree,
// rewrites a scene of an older `version` into the current one in memory before any plugin reads
// it). It runs once on a ParsedScene (core/xml/xml_parser.h), before the loader hands any
// Properties to a plugin, and does two things:
//
//   1. Version rules that are a matter of spelling: what a Mitsuba 0.6 scene (a version 0.x file;
//      Properties::formatVersion) writes differently from a Mitsuba 3 one is rewritten into the
//      Mitsuba 3 form, so that plugins read one form:
//        camelCase parameter names → snake_case (toWorld → to_world; upgrade_tree does the same)
//        a single-valued <spectrum value="v"/> → the number v (Mitsuba 0.6 reads it as a number,
//          v × D65 for an emitter; Mitsuba 3 reads it as a flat spectrum)
//        conductor, roughconductor: no material, eta or k → material "Cu" (Mitsuba 0.6's default);
//          extEta → ext_ior; neither → ext_ior 1.000277 ("air", Mitsuba 0.6's default)
//        normalmap, bumpmap: flip_invalid_normals and use_shadowing_function false unless given
//          (Mitsuba 0.6's wrappers had neither option)
//        principled → disney (Mitsuba 0.6 has none; iris's `principled` was Disney 2012 before)
//      and rules that choose between the two Mitsubas' models, so that iris renders an old scene as
//      the old Mitsuba did, are written as parameters the plugins read (core/mitsuba_convention.h):
//        roughplastic, blendbsdf, mask, conductor, roughconductor, checkerboard, envmap and the
//          regular/irregular spectra get `convention` "mitsuba0.6" unless the scene gives one
//        every tabulated spectrum value (λ:v pairs, a .spd file) gets SpectrumValue::convention
//          Mitsuba06 (its RGB-mode value, spectral/mitsuba_rgb.h)
//      No plugin reads Properties::formatVersion (tests/architecture/check_format_version.py).
//   2. Defaults (render/scene_defaults.h, the one table): a scene without <integrator> gets one,
//      a scene without <sensor> gets one, a sensor without <film> or <sampler> gets them, a film
//      without <rfilter> gets one.
// The version attribute itself is checked by the parser (an unsupported version is refused with
// file and line, core/xml/xml_parser.cpp), which records the major version on every Properties.
#pragma once

#include "core/xml/xml_parser.h"

namespace iris {

/// Apply the version rules and fill the defaults, in place (see the file comment). Each object is
/// upgraded once, also when several objects refer to it.
void upgradeScene(ParsedScene& scene);

/// The version rules alone, for one object and the objects nested in it (each by its own
/// Properties::formatVersion): for objects built in code that stand for a file's.
void upgradeObject(Properties& p);

}  // namespace iris
