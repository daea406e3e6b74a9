// The signed distance of a sphere sampled as an SDF grid (core/sdf_grid.h: sample (i, j, k) at
// (i, j, k)/(n − 1) of the unit cube), for the sdfgrid tests, and bounds on how far the zero set of
// its trilinear interpolant and that set's normals lie from the sphere's.
#pragma once

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/math.h"
#include "tests/support/vol_file.h"

namespace iris::test {

/// f(x) = |x − c| − r at the n³ samples of the unit cube.
inline std::vector<float> sphereSdfSamples(int n, const vec3& c, float r) {
    std::vector<float> v;
    for (int k = 0; k < n; ++k)
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) v.push_back(glm::length(vec3(i, j, k) / float(n - 1) - c) - r);
    return v;
}

/// The same written as a 1-channel .vol file in the test's temporary folder.
inline std::string writeSphereSdf(const std::string& folder, const std::string& name, int n, const vec3& c, float r) {
    return writeVolFile(folder, name, ivec3(n), 1, sphereSdfSamples(n, c, r));
}

/// Error bounds of the trilinear interpolant I f of a sphere's distance f (radius r) sampled with
/// spacing h = 1/(n − 1), in the cells the surface crosses, where the distance ρ to the centre is
/// at least ρ_min = r − √3 h. The distance's Hessian is H = (I − n nᵀ)/ρ (diagonal sum 2/ρ) and its
/// third derivatives are at most 3/ρ².
///  - Gradient: ∂_a I f is a bilinear blend of the difference quotients along the cell's 4 edges
///    parallel to a, each f_a at the edge's midpoint up to h²/24·|f_aaa| (midpoint rule); the
///    blend reproduces linear functions, so to first order it is f_a at (mid_a, p_b, p_c), off by
///    H_aa·(mid_a − p_a), |mid_a − p_a| ≤ h/2. The vector of those is at most (h/2)·√(Σ H_aa²) ≤
///    (√2/2)·h/ρ, and tangential (H maps every offset into the tangent plane); the second-order
///    rest (midpoint rule and Taylor remainders) is at most 1.25·h²·3/ρ² per component ≤ 2.2 h²/ρ²
///    as a vector. So |∇ I f − ∇f| ≤ e = (√2/2) h/ρ_min + 2.2 h²/ρ_min², and the normal's angle is
///    at most asin(e).
///  - Position: interpolation errs by at most h²/8·(|f_xx| + |f_yy| + |f_zz|) ≤ h²/(4ρ_min); a value
///    error moves the zero set by that over |∇ I f|, whose component along the normal is off by the
///    second-order rest only: |∇ I f| ≥ 1 − 2.2 h²/ρ_min².
inline double sphereSdfNormalBound(int n, double r) {
    const double h = 1.0 / (n - 1), rhoMin = r - std::sqrt(3.0) * h;
    return std::asin(std::min(1.0, std::sqrt(0.5) * h / rhoMin + 2.2 * h * h / (rhoMin * rhoMin)));
}

inline double sphereSdfPositionBound(int n, double r) {
    const double h = 1.0 / (n - 1), rhoMin = r - std::sqrt(3.0) * h;
    return h * h / (4.0 * rhoMin) / (1.0 - 2.2 * h * h / (rhoMin * rhoMin));
}

}  // namespace iris::test
