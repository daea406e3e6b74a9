// The ray test of one surface voxel of an SDF grid (core/sdf_grid.h), exact and in double
// precision, as Mitsuba 3 does (src/shapes/sdfgrid.cpp; Hansson-Söderlund, Evans & Akenine-Möller
// 2022, "Ray Tracing of Signed Distance Function Grids", JCGT 11(3)): along the ray the
// trilinear interpolant is a cubic in t; the roots of its derivative split the voxel's piece of the
// ray into monotonic intervals (Marmitt et al. 2004, "Fast and accurate ray-voxel intersection
// techniques for iso-surface ray tracing"), and the first interval whose ends differ in sign holds
// the first crossing, found by Newton's method safeguarded by bisection. No step size or Lipschitz
// bound is needed, and non-uniform to_world scales (which stop the samples from being distances)
// change nothing.
//
// Consistency between voxels: the values at the points where the ray enters and leaves a voxel are
// the trilinear interpolant with the crossed face's coordinate set exactly to 0 or 1, so two
// neighbours compute bit-identical values on their shared face and a crossing there is seen by at
// least one of them (the intervals are closed).
//
// Rays starting on the surface: when the ray starts in the voxel (within 1e-4 of a voxel) at a
// point where |f| ≤ 1e-4 of the voxel's largest corner value, the first monotonic interval is
// skipped — the only crossing it can hold is the surface the ray starts on, whatever side rounding
// put the origin on. Spawned rays are offset off the surface as well (offsetRayOrigin).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/math.h"
#include "core/sdf_grid.h"

namespace iris {

namespace sdf_detail {

/// A cubic c0 + c1 x + c2 x² + c3 x³.
struct Cubic {
    double c[4] = {0, 0, 0, 0};
    double operator()(double x) const { return ((c[3] * x + c[2]) * x + c[1]) * x + c[0]; }
    double derivative(double x) const { return (3 * c[3] * x + 2 * c[2]) * x + c[1]; }
};

/// The piece [t0, t1] ∩ [tMin, tMax] of the ray o + t·d (grid coordinates) in voxel v = [v, v + 1],
/// and the axes of the faces it enters and leaves by (−1 where tMin or tMax cuts it instead).
struct VoxelSpan {
    double t0 = 0, t1 = 0;
    int entry = -1, exit = -1;
};

inline bool clipToVoxel(const dvec3& o, const dvec3& d, const ivec3& v, double tMin, double tMax, VoxelSpan& s) {
    s = VoxelSpan{tMin, tMax, -1, -1};
    for (int a = 0; a < 3; ++a) {
        const double lo = double(v[a]), hi = double(v[a]) + 1.0;
        if (d[a] == 0) {
            if (o[a] < lo || o[a] > hi) return false;
            continue;
        }
        double tLo = (lo - o[a]) / d[a], tHi = (hi - o[a]) / d[a];
        if (tLo > tHi) std::swap(tLo, tHi);
        if (tLo > s.t0) s.t0 = tLo, s.entry = a;
        if (tHi < s.t1) s.t1 = tHi, s.exit = a;
    }
    return s.t0 <= s.t1;
}

/// The voxel-local point of the ray at t, in [0, 1]³, with the coordinate of the crossed face (if
/// any) exactly 0 or 1.
inline dvec3 localPoint(const dvec3& o, const dvec3& d, const ivec3& v, double t, int face, bool entering) {
    dvec3 q;
    for (int a = 0; a < 3; ++a) q[a] = std::clamp((o[a] - double(v[a])) + t * d[a], 0.0, 1.0);
    if (face >= 0) q[face] = (d[face] > 0) == entering ? 0.0 : 1.0;
    return q;
}

/// The trilinear interpolant along q0 + x·d as a cubic in x: the sum over corners of s_c times the
/// product of the three linear weights (q or 1 − q per axis).
inline Cubic voxelCubic(const double (&s)[8], const dvec3& q0, const dvec3& d) {
    Cubic f;
    for (int c = 0; c < 8; ++c) {
        double p[4] = {1, 0, 0, 0};
        for (int a = 0; a < 3; ++a) {
            const bool upper = (c >> a) & 1;
            const double alpha = upper ? q0[a] : 1.0 - q0[a], beta = upper ? d[a] : -d[a];
            for (int k = 3; k >= 1; --k) p[k] = p[k] * alpha + p[k - 1] * beta;
            p[0] *= alpha;
        }
        for (int k = 0; k < 4; ++k) f.c[k] += s[c] * p[k];
    }
    return f;
}

/// The roots of f' in (0, T), ascending, appended to x after x[0] = 0; returns the new count.
inline int addCriticalPoints(const Cubic& f, double T, double* x, int n) {
    const double a = 3 * f.c[3], b = f.c[2], c = f.c[1];  // f' = a x² + 2 b x + c
    double r[2];
    int m = 0;
    if (a != 0) {
        const double disc = b * b - a * c;
        if (disc >= 0) stableQuadraticRoots(a, b, c, disc, r[0], r[1]), m = 2;
    } else if (b != 0) {
        r[0] = -c / (2 * b), m = 1;
    }
    for (int i = 0; i < m; ++i)
        if (r[i] > 0 && r[i] < T && r[i] > x[n - 1]) x[n++] = r[i];
    return n;
}

/// The root of f in [lo, hi], where f(lo) has the sign of `fLo` and f(hi) the other one (or is 0):
/// Newton's method from the secant estimate, bisecting whenever a step leaves the bracket.
inline double solveBracketed(const Cubic& f, double lo, double hi, double fLo, double fHi) {
    double x = fHi != fLo ? lo + (hi - lo) * (fLo / (fLo - fHi)) : 0.5 * (lo + hi);
    if (!(x >= lo && x <= hi)) x = 0.5 * (lo + hi);
    for (int i = 0; i < 100; ++i) {
        const double fx = f(x);
        if (fx == 0) return x;
        ((fx < 0) == (fLo < 0) ? lo : hi) = x;
        double next = x - fx / f.derivative(x);
        if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
        if (std::abs(next - x) <= 1e-14 * std::max(1.0, std::abs(x))) return next;
        x = next;
    }
    return x;
}

}  // namespace sdf_detail

/// The smallest t in (tMin, tMax] at which o + t·d (the shape's space) crosses the surface inside
/// surface voxel `prim` of g, or +infinity.
inline double intersectSdfVoxel(const SdfGrid& g, uint32_t prim, const dvec3& oShape, const dvec3& dShape, double tMin,
                                double tMax) {
    using namespace sdf_detail;
    constexpr double kNone = std::numeric_limits<double>::infinity();
    const dvec3 o(g.toGrid * glm::dvec4(oShape, 1.0)), d(glm::dmat3(g.toGrid) * dShape);
    const ivec3 v = g.voxel(prim);
    VoxelSpan span;
    if (!(glm::dot(d, d) > 0) || !clipToVoxel(o, d, v, tMin, tMax, span)) return kNone;
    double s[8];
    g.corners(v, s);
    const dvec3 q0 = localPoint(o, d, v, span.t0, span.entry, true), q1 = localPoint(o, d, v, span.t1, span.exit, false);
    const Cubic f = voxelCubic(s, q0, d);
    const double T = span.t1 - span.t0;
    double x[4] = {0, 0, 0, 0}, fx[4];
    int n = addCriticalPoints(f, T, x, 1);
    x[n++] = T;
    fx[0] = trilinear(s, q0);
    fx[n - 1] = trilinear(s, q1);
    for (int i = 1; i + 1 < n; ++i) fx[i] = f(x[i]);
    double largest = 0;
    for (double c : s) largest = std::max(largest, std::abs(c));
    const bool startsOnSurface = (span.t0 - tMin) * glm::length(d) <= 1e-4 && std::abs(fx[0]) <= 1e-4 * largest;
    for (int i = startsOnSurface ? 1 : 0; i + 1 < n; ++i) {
        if (!(fx[i] * fx[i + 1] <= 0)) continue;
        const double r = fx[i] == 0 ? x[i] : solveBracketed(f, x[i], x[i + 1], fx[i], fx[i + 1]);
        const double t = span.t0 + r;
        if (t > tMin && t <= tMax) return t;
    }
    return kNone;
}

}  // namespace iris
