// Mitsuba plugins iris cannot honour, with what to use instead: their "unknown <tag> type"
// errors (core/registry.h) end with this advice.
#include "render/integrator.h"
#include "render/lights/light.h"
#include "materials/material.h"

namespace iris {

IRIS_HINT(MaterialRegistry, "hair", "iris has no hair BSDF: use roughconductor or roughdielectric as an approximation");
IRIS_HINT(LightRegistry, "projector", "iris has no projector emitter: use 'spot' (a cone of constant intensity)");
IRIS_HINT(LightRegistry, "sunsky", "iris has no sky model: use 'envmap' with a rendered sky image");
IRIS_HINT(LightRegistry, "sky", "iris has no sky model: use 'envmap' with a rendered sky image");
IRIS_HINT(LightRegistry, "sun", "iris has no sun model: use 'directional'");
IRIS_HINT(IntegratorRegistry, "bdpt", "use 'path' (unbiased, more noise on caustics)");

}  // namespace iris
