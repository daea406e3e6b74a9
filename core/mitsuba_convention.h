// Whose model a plugin evaluates where Mitsuba 0.6 and Mitsuba 3 differ (docs/scene_format.md,
// "Version-dependent defaults"). The upgrade pass (render/loader/scene_upgrade.h) is the one place
// that maps a scene's `version` to a convention: it writes `convention` "mitsuba0.6" into the
// objects of a version 0.x file whose plugin has two models, and marks the tabulated spectrum values
// of such a file (SpectrumValue::convention). Plugins read the parameter, never the version, so a
// Mitsuba 3 scene (or code) can also ask for Mitsuba 0.6's model of one object.
#pragma once

#include <string>

namespace iris {

enum class MitsubaConvention { Mitsuba06, Mitsuba3 };

class Properties;

/// The `convention` parameter of `p`: "mitsuba3" (the default) or "mitsuba0.6"; another value is
/// an error at the parameter's line naming both.
MitsubaConvention getConvention(const Properties& p);

/// The parameter's spelling of `c` ("mitsuba0.6", "mitsuba3").
const char* conventionName(MitsubaConvention c);

}  // namespace iris
