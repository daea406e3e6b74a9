// Ray-sphere intersection, analytic, in double precision (issue 17 item 1): the scene traces
// spheres as Embree user geometry with this test instead of Embree's sphere-point primitive.
#pragma once

#include <cmath>
#include <limits>

#include "core/math.h"

namespace iris {

/// The smallest t in (tMin, tMax] at which o + t·d lies on the sphere (center c, radius r), or
/// +infinity. The quadratic a t² + 2 b' t + c' = 0 with a = d·d, b' = f·d, c' = f·f − r², f = o − c,
/// solved as Haines et al., "Precision Improvements for Ray/Sphere Intersection" (Ray Tracing Gems,
/// 2019, ch. 7): the discriminant as a·(r² − |f − (b'/a) d|²) (eq. 7.5), which does not cancel when
/// the ray starts far away, and the two roots as q/a and c'/q with q = −(b' + sign(b')·√Δ) (eq. 7.4
/// and Numerical Recipes §5.6), which do not cancel when they differ greatly.
inline double intersectSphere(const dvec3& o, const dvec3& d, const dvec3& c, double r, double tMin, double tMax) {
    const dvec3 f = o - c;
    const double a = glm::dot(d, d);
    const double b = glm::dot(f, d);
    const dvec3 l = f - (b / a) * d;  // f minus its projection on d: the ray's closest approach to c
    const double disc = a * (r * r - glm::dot(l, l));
    if (!(disc >= 0)) return std::numeric_limits<double>::infinity();
    double t0, t1;
    stableQuadraticRoots(a, b, glm::dot(f, f) - r * r, disc, t0, t1);
    if (t0 > tMin && t0 <= tMax) return t0;
    if (t1 > tMin && t1 <= tMax) return t1;
    return std::numeric_limits<double>::infinity();
}

/// Mitsuba 3's sphere parametrisation (src/shapes/sphere.cpp) of the unit vector n from the
/// centre: u = φ/2π with φ = atan2(n.y, n.x) in [0, 2π), v = θ/π with θ = acos(n.z).
inline vec2 sphereUV(const vec3& n) {
    const float phi = std::atan2(n.y, n.x);
    return vec2((phi < 0 ? phi + 2 * kPi : phi) * kInv2Pi, safeAcos(n.z) * kInvPi);
}

}  // namespace iris
