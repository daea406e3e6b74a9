// Irradiance from a uniformly emitting square, in closed form: Lambert's polygon formula
// E = (L/2) Σ_edges β_i (n · u_i), β_i the angle edge i subtends at the receiver and u_i the unit
// normal of the plane through the receiver and that edge (Arvo 1994, "The Irradiance Jacobian for
// Partially Occluded Polyhedral Sources", eq. 1).
#pragma once

#include <algorithm>
#include <cmath>

#include "core/math.h"

namespace iris::test {

/// Irradiance at the origin (normal +z) from a square of half-size a at height h, parallel to the
/// receiver and centred above it, emitting radiance L towards it.
inline double squareLightIrradiance(float a, float h, float L) {
    const vec3 corners[4] = {{-a, -a, h}, {a, -a, h}, {a, a, h}, {-a, a, h}};
    double E = 0;
    for (int i = 0; i < 4; ++i) {
        const vec3 v0 = glm::normalize(corners[i]), v1 = glm::normalize(corners[(i + 1) % 4]);
        const double beta = std::acos(std::clamp(double(glm::dot(v0, v1)), -1.0, 1.0));
        const vec3 u = glm::normalize(glm::cross(v0, v1));
        E += 0.5 * L * beta * std::abs(u.z);
    }
    return E;
}

}  // namespace iris::test
