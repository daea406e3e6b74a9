// A signed-distance grid (Mitsuba 3 `sdfgrid`, src/shapes/sdfgrid.cpp): samples of a signed
// distance on a regular grid over the unit cube, placed by to_world; the surface is the zero set of
// their trilinear interpolant, negative inside. Conventions of Mitsuba 3:
//  - res = (nx, ny, nz) samples, sample (i, j, k) at the object-space point (i/(nx−1), j/(ny−1),
//    k/(nz−1)) (the samples sit on the cube's corners and faces, unlike a gridvolume's cell-centred
//    voxels), stored x fastest: ((k·ny + j)·nx + i), the layout of a 1-channel .vol file;
//  - a voxel is the cell between 2×2×2 samples; one whose corners are not all > 0 or all < 0 may
//    hold surface and becomes one ray-tracing primitive (Embree user geometry, render/scene.cpp).
// Grid coordinates g = (nx−1, ny−1, nz−1)·object: sample (i, j, k) is at g = (i, j, k), and voxel v
// covers [v, v + 1]. The ray test is core/sdf_grid_intersection.h, the normals sdf_grid.cpp.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/math.h"

namespace iris {

/// Linear interpolation (1 − w)·a + w·b: exactly a at w = 0 and b at w = 1, so that two voxels
/// interpolate bit for bit alike on the face they share (the ray test relies on it).
inline double lerpExact(double a, double b, double w) { return (1.0 - w) * a + w * b; }

/// The trilinear interpolant of the 8 corner values s[c] (corner c at (c & 1, c >> 1 & 1, c >> 2))
/// at q in [0, 1]³: along x, then y, then z.
inline double trilinear(const double (&s)[8], const dvec3& q) {
    const double y0 = lerpExact(lerpExact(s[0], s[1], q.x), lerpExact(s[2], s[3], q.x), q.y);
    const double y1 = lerpExact(lerpExact(s[4], s[5], q.x), lerpExact(s[6], s[7], q.x), q.y);
    return lerpExact(y0, y1, q.z);
}

/// Its gradient with respect to q: each partial derivative is the bilinear interpolant of the
/// differences along the four edges parallel to its axis.
inline dvec3 trilinearGradient(const double (&s)[8], const dvec3& q) {
    auto bilinear = [](double a, double b, double c, double d, double u, double v) { return lerpExact(lerpExact(a, b, u), lerpExact(c, d, u), v); };
    return dvec3(bilinear(s[1] - s[0], s[3] - s[2], s[5] - s[4], s[7] - s[6], q.y, q.z),
                 bilinear(s[2] - s[0], s[3] - s[1], s[6] - s[4], s[7] - s[5], q.x, q.z),
                 bilinear(s[4] - s[0], s[5] - s[1], s[6] - s[2], s[7] - s[3], q.x, q.y));
}

struct SdfGrid {
    ivec3 res{2};                 // samples per axis, each ≥ 2
    std::vector<float> values;    // ((k·ny + j)·nx + i)
    std::vector<uint32_t> voxels; // the sample index of each surface voxel's lower corner
    mat4 toWorld{1.0f};           // object (unit cube) → the shape's space (world, or a shape group's)
    glm::dmat4 toGrid{1.0};       // the shape's space → grid coordinates
    bool smoothNormals = true;    // Mitsuba 3 normals="smooth" (default) or "analytic"
    bool closed = false;          // every sample on the grid's boundary is > 0: the surface is closed

    double at(int i, int j, int k) const { return values[(size_t(k) * size_t(res.y) + size_t(j)) * size_t(res.x) + size_t(i)]; }
    /// The lower corner of surface voxel `prim`.
    ivec3 voxel(uint32_t prim) const {
        const uint32_t index = voxels[prim], nx = uint32_t(res.x), ny = uint32_t(res.y);
        return ivec3(int(index % nx), int(index / nx % ny), int(index / (nx * ny)));
    }
    void corners(const ivec3& v, double (&s)[8]) const {
        for (int c = 0; c < 8; ++c) s[c] = at(v.x + (c & 1), v.y + (c >> 1 & 1), v.z + (c >> 2));
    }
    /// The bounds of voxel `prim` in the shape's space (its 8 corners mapped by toWorld).
    void voxelBounds(uint32_t prim, vec3& lo, vec3& hi) const;
    /// The geometric normal at p (the shape's space) in surface voxel `prim`: the normalised
    /// gradient of the trilinear interpolant, pointing to positive distances (outwards).
    vec3 analyticNormal(uint32_t prim, const vec3& p) const;
    /// The smooth shading normal at p (see sdf_grid.cpp), or the analytic one for "analytic".
    vec3 shadingNormal(uint32_t prim, const vec3& p) const;
    /// p moved along the gradient onto the zero set by one Newton step (kept when it stays in the
    /// voxel and lowers |f|), which reduces the error of a hit point rounded to float.
    vec3 projectOntoSurface(uint32_t prim, const vec3& p) const;
};

/// A grid from its samples: each resolution ≥ 2, values finite, toWorld invertible and finite; the
/// surface voxels listed (memory charged first, naming `what`); at least one surface voxel.
/// Throws iris::Error naming `what` (the file) on bad input.
SdfGrid makeSdfGrid(ivec3 res, std::vector<float> values, const mat4& toWorld, bool smoothNormals, const std::string& what);

}  // namespace iris
