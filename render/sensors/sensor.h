// Sensors (Mitsuba's <sensor>): generate the primary ray through a film position. A sensor is
// created once its film's size is known (the field of view and the aspect ratio need it).
#pragma once

#include <memory>

#include "core/ray.h"
#include "core/registry.h"

namespace iris {

struct FilmSize {
    int width = 0, height = 0;
};

class Sensor {
public:
    /// `toWorld`: the sensor looks along +z of this frame with +y up (Mitsuba's convention).
    explicit Sensor(const mat4& toWorld) : toWorld_(toWorld) {}
    virtual ~Sensor() = default;
    /// Primary ray through film position (x, y) in pixels (0,0 = top-left corner). Direction is unit.
    virtual Ray generateRay(const vec2& filmPos) const = 0;
    const mat4& toWorld() const { return toWorld_; }

private:
    mat4 toWorld_;
};

using SensorPtr = std::shared_ptr<const Sensor>;
using SensorRegistry = Registry<Sensor, FilmSize>;

}  // namespace iris
