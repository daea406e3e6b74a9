#include "render/sensors/sensor.h"

#include "core/error.h"

namespace iris {

std::optional<SensorSample> Sensor::sampleWi(const vec3&) const {
    fail("this sensor type has no importance function: light tracing (ptracer, bdpt) needs a perspective or "
         "orthographic sensor");
}

}  // namespace iris
