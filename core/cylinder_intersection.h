// The open cylinder (Mitsuba "cylinder", no end caps) as the scene traces it: its world-space
// geometry and the analytic ray test in double precision. The scene traces cylinders as Embree
// user geometry with this test (render/scene.cpp), as it does spheres (sphere_intersection.h).
#pragma once

#include <cmath>
#include <limits>

#include "core/math.h"

namespace iris {

/// A cylinder in world space: the centre line from p0 along the unit `axis` for `length`, and the
/// unit vectors s, t that complete the frame (s × t = axis unless to_world mirrors) in which the angle φ of
/// the uv parametrisation is measured (Mitsuba 3 src/shapes/cylinder.cpp: Frame3f(axis), the
/// orthonormal basis of Duff et al. 2017 — iris's Frame::fromNormal).
struct CylinderGeometry {
    vec3 p0{0.0f};
    vec3 axis{0, 0, 1}, s{1, 0, 0}, t{0, 1, 0};
    float length = 1.0f;
};

/// The smallest t in (tMin, tMax] at which o + t·d lies on the open cylinder of radius r, or
/// +infinity. With f = o − p0 and the parts of f and d perpendicular to the axis, f⊥ and d⊥, the
/// hits solve |f⊥ + t d⊥|² = r²: a t² + 2 b' t + c' = 0 with a = d⊥·d⊥, b' = f⊥·d⊥,
/// c' = f⊥·f⊥ − r², solved as the sphere's (Haines et al. 2019, Ray Tracing Gems ch. 7: the
/// discriminant a·(r² − |f⊥ − (b'/a) d⊥|²) and the roots q/a, c'/q); a root counts only where the
/// hit's position along the axis is within [0, length].
inline double intersectCylinder(const dvec3& o, const dvec3& d, const CylinderGeometry& c, double r, double tMin,
                                double tMax) {
    const dvec3 axis(c.axis);
    const dvec3 f = o - dvec3(c.p0);
    const double fz = glm::dot(f, axis), dz = glm::dot(d, axis);
    const dvec3 fp = f - fz * axis, dp = d - dz * axis;
    const double a = glm::dot(dp, dp);
    if (!(a > 0)) return std::numeric_limits<double>::infinity();  // parallel to the axis: no wall hit
    const double b = glm::dot(fp, dp);
    const dvec3 l = fp - (b / a) * dp;  // the ray's closest approach to the axis, perpendicular part
    const double disc = a * (r * r - glm::dot(l, l));
    if (!(disc >= 0)) return std::numeric_limits<double>::infinity();
    double t0, t1;
    stableQuadraticRoots(a, b, glm::dot(fp, fp) - r * r, disc, t0, t1);
    for (const double t : {t0, t1}) {
        const double z = fz + t * dz;
        if (t > tMin && t <= tMax && z >= 0 && z <= double(c.length)) return t;
    }
    return std::numeric_limits<double>::infinity();
}

}  // namespace iris
