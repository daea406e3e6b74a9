// Mitsuba plugins iris cannot honour, with what to use instead: their "unknown <tag> type"
// errors (core/registry.h) end with this advice.
#include "render/integrator.h"
#include "render/lights/light.h"
#include "render/sensors/sensor.h"
#include "render/shapes/shape.h"
#include "materials/material.h"

namespace iris {

IRIS_HINT(MaterialRegistry, "measured_polarized",
          "iris cannot read Mitsuba 3's measured pBRDF files (.pbsdf; docs/polarization.md says what is missing): use "
          "'pplastic' or 'roughconductor' as an approximation");
IRIS_HINT(MaterialRegistry, "hair", "iris has no hair BSDF: use roughconductor or roughdielectric as an approximation");
IRIS_HINT(LightRegistry, "sunsky", "iris has no sky model: use 'envmap' with a rendered sky image");
IRIS_HINT(LightRegistry, "sky", "iris has no sky model: use 'envmap' with a rendered sky image");
IRIS_HINT(LightRegistry, "sun", "iris has no sun model: use 'directional'");
IRIS_HINT(LightRegistry, "volumelight", "a volumelight belongs to a medium: nest it in the <medium>, or attach it to a shape "
                                       "whose interior medium it then makes emit");
IRIS_HINT(IntegratorRegistry, "aov", "iris writes no AOV images: the 'moment' wrapper gives per-pixel first and second moments");
IRIS_HINT(SensorRegistry, "thinlens", "iris has no depth of field: use 'perspective' (a pinhole, everything in focus)");
IRIS_HINT(ShapeRegistry, "bsplinecurve", "iris has no curve shapes: convert the curves to a mesh (obj or ply)");
IRIS_HINT(ShapeRegistry, "linearcurve", "iris has no curve shapes: convert the curves to a mesh (obj or ply)");

}  // namespace iris
