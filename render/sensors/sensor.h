// Sensors (Mitsuba's <sensor>): generate the primary ray through a film position. A sensor is
// created once its film's size is known (the field of view and the aspect ratio need it).
#pragma once

#include <memory>
#include <optional>

#include "core/ray.h"
#include "core/registry.h"

namespace iris {

struct FilmSize {
    int width = 0, height = 0;
};

/// A scene point as the sensor sees it, for paths that reach the sensor from the light side (light
/// tracing and BDPT's t = 1 strategies; Veach 1997 §10.2, pbrt-v4 §5.4 Camera::SampleWi).
struct SensorSample {
    vec3 pSensor{0.0f};   // the point on the sensor the connection ends at
    vec3 wi{0.0f};        // unit direction from the scene point towards pSensor
    float dist = 0.0f;    // distance from the scene point to pSensor
    vec2 filmPos{0.0f};   // film position in pixels (may lie outside the image: the filter decides)
    /// The sensor's importance over the density of the connection: a light-path vertex with
    /// throughput β, BSDF value f and |cos θ| towards the sensor adds β f |cos θ| · weight, for the
    /// image as a whole (the importance is normalised so that it integrates to width × height
    /// over the film in pixel units: per pixel, one light path per pixel adds up to the pixel's
    /// value). Perspective: W H / (A cos³θ d²) with A the image's area on the plane z = 1;
    /// orthographic: W H / A⊥, A⊥ the film's area perpendicular to the view direction.
    float weight = 0.0f;
};

class Sensor {
public:
    /// `toWorld`: the sensor looks along +z of this frame with +y up (Mitsuba's convention).
    explicit Sensor(const mat4& toWorld) : toWorld_(toWorld) {}
    virtual ~Sensor() = default;
    /// Primary ray through film position (x, y) in pixels (0,0 = top-left corner). Direction is unit.
    virtual Ray generateRay(const vec2& filmPos) const = 0;
    const mat4& toWorld() const { return toWorld_; }

    /// The connection of scene point p to the sensor, nullopt when the sensor cannot see p (behind
    /// it). Sensors without an importance function refuse light tracing with an error.
    virtual std::optional<SensorSample> sampleWi(const vec3& p) const;
    /// The pinhole's position, for sensors that have one (directions from it reach the film).
    virtual std::optional<vec3> pinhole() const { return std::nullopt; }
    /// For BDPT's MIS: the solid-angle density of a camera ray's direction w when the film position
    /// is uniform over the image, 1 / (A cos³θ) (pbrt-v4 §5.4.1 PerspectiveCamera::PDF_We), for any
    /// w in front of the pinhole; 0 for sensors without a pinhole.
    virtual float pdfDirection(const vec3& w) const { return (void)w, 0.0f; }

private:
    mat4 toWorld_;
};

using SensorPtr = std::shared_ptr<const Sensor>;
using SensorRegistry = Registry<Sensor, FilmSize>;

}  // namespace iris
