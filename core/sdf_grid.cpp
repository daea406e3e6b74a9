#include "core/sdf_grid.h"

#include <cmath>
#include <limits>

#include "core/error.h"
#include "core/memory_budget.h"

namespace iris {

namespace {

bool finiteMatrix(const mat4& m) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(m[c][r])) return false;
    return true;
}

void checkSamples(const ivec3& res, const std::vector<float>& values, const std::string& what) {
    if (res.x < 2 || res.y < 2 || res.z < 2)
        fail(what, ": an sdfgrid needs at least 2 samples along each axis (its voxels span 1/(n − 1) of the unit cube), this "
             "grid has ", res.x, "x", res.y, "x", res.z);
    if (uint64_t(res.x) * uint64_t(res.y) * uint64_t(res.z) >= (uint64_t(1) << 32))
        fail(what, ": an sdfgrid of ", res.x, "x", res.y, "x", res.z, " samples is too large (at most 2^32 samples)");
    if (values.size() != size_t(res.x) * size_t(res.y) * size_t(res.z))
        fail(what, ": ", values.size(), " samples for a grid of ", res.x, "x", res.y, "x", res.z);
    for (size_t i = 0; i < values.size(); ++i)
        if (!std::isfinite(values[i]))
            fail(what, ": non-finite sdfgrid sample ", values[i], " at (", i % size_t(res.x), ", ", i / size_t(res.x) % size_t(res.y),
                 ", ", i / (size_t(res.x) * size_t(res.y)), ")");
}

/// Whether voxel v may hold surface: its corners are not all > 0 nor all < 0 (Mitsuba 3 keeps
/// voxels with a corner ≥ 0 and one ≤ 0).
bool holdsSurface(const SdfGrid& g, const ivec3& v) {
    double s[8];
    g.corners(v, s);
    bool nonNegative = false, nonPositive = false;
    for (double c : s) nonNegative |= c >= 0, nonPositive |= c <= 0;
    return nonNegative && nonPositive;
}

template <class F>
void forEachVoxel(const ivec3& res, F&& f) {
    for (int k = 0; k + 1 < res.z; ++k)
        for (int j = 0; j + 1 < res.y; ++j)
            for (int i = 0; i + 1 < res.x; ++i) f(ivec3(i, j, k));
}

void listSurfaceVoxels(SdfGrid& g, const std::string& what) {
    size_t count = 0;
    forEachVoxel(g.res, [&](const ivec3& v) { count += holdsSurface(g, v); });
    if (count == 0) fail(what, ": the sdfgrid has no surface (no voxel has samples both <= 0 and >= 0)");
    chargeMemory(count * sizeof(uint32_t), strCat(what, ": ", count, " surface voxels of an sdfgrid"));
    g.voxels.reserve(count);
    forEachVoxel(g.res, [&](const ivec3& v) {
        if (holdsSurface(g, v)) g.voxels.push_back(uint32_t((size_t(v.z) * size_t(g.res.y) + size_t(v.y)) * size_t(g.res.x) + size_t(v.x)));
    });
}

/// True when every sample on the grid's six faces is > 0: the zero set stays inside the grid.
bool boundaryPositive(const SdfGrid& g) {
    for (int k = 0; k < g.res.z; ++k)
        for (int j = 0; j < g.res.y; ++j)
            for (int i = 0; i < g.res.x; ++i) {
                const bool onFace = i == 0 || j == 0 || k == 0 || i == g.res.x - 1 || j == g.res.y - 1 || k == g.res.z - 1;
                if (onFace && !(g.at(i, j, k) > 0)) return false;
            }
    return true;
}

/// The gradient `grad` of grid coordinates carried to the shape's space: ∇ₓf = J^T ∇_g f, with J
/// the linear part of toGrid.
dvec3 toShapeGradient(const SdfGrid& g, const dvec3& grad) { return glm::transpose(glm::dmat3(g.toGrid)) * grad; }

dvec3 gridPoint(const SdfGrid& g, const vec3& p) { return dvec3(g.toGrid * glm::dvec4(dvec3(p), 1.0)); }

vec3 unitOr(const dvec3& v, const vec3& fallback) {
    const double len = glm::length(v);
    return len > 0 && std::isfinite(len) ? vec3(v / len) : fallback;
}

}  // namespace

SdfGrid makeSdfGrid(ivec3 res, std::vector<float> values, const mat4& toWorld, bool smoothNormals, const std::string& what) {
    checkSamples(res, values, what);
    const float det = glm::determinant(mat3(toWorld));
    if (!finiteMatrix(toWorld) || !std::isfinite(det) || std::abs(det) < 1e-30f)
        fail(what, ": the sdfgrid's to_world must be an invertible, finite transform");
    SdfGrid g;
    g.res = res;
    g.values = std::move(values);
    g.toWorld = toWorld;
    g.toGrid = glm::scale(glm::dmat4(1.0), dvec3(res - 1)) * glm::inverse(glm::dmat4(toWorld));
    g.smoothNormals = smoothNormals;
    listSurfaceVoxels(g, what);
    g.closed = boundaryPositive(g);
    return g;
}

void SdfGrid::voxelBounds(uint32_t prim, vec3& lo, vec3& hi) const {
    const ivec3 v = voxel(prim);
    const vec3 step = 1.0f / vec3(res - 1);
    lo = vec3(std::numeric_limits<float>::infinity());
    hi = -lo;
    for (int c = 0; c < 8; ++c) {
        const vec3 corner = vec3(v + ivec3(c & 1, c >> 1 & 1, c >> 2)) * step;
        const vec3 q = transformPoint(toWorld, corner);
        lo = glm::min(lo, q);
        hi = glm::max(hi, q);
    }
}

vec3 SdfGrid::analyticNormal(uint32_t prim, const vec3& p) const {
    const ivec3 v = voxel(prim);
    double s[8];
    corners(v, s);
    const dvec3 q = glm::clamp(gridPoint(*this, p) - dvec3(v), 0.0, 1.0);
    const vec3 atCentre = unitOr(toShapeGradient(*this, trilinearGradient(s, dvec3(0.5))), vec3(0, 0, 1));
    return unitOr(toShapeGradient(*this, trilinearGradient(s, q)), atCentre);
}

vec3 SdfGrid::projectOntoSurface(uint32_t prim, const vec3& p) const {
    const ivec3 v = voxel(prim);
    double s[8];
    corners(v, s);
    const dvec3 q = gridPoint(*this, p) - dvec3(v);
    const double f = trilinear(s, glm::clamp(q, 0.0, 1.0));
    const dvec3 grad = toShapeGradient(*this, trilinearGradient(s, glm::clamp(q, 0.0, 1.0)));
    const double g2 = glm::dot(grad, grad);
    if (!(g2 > 0) || !std::isfinite(f)) return p;
    const vec3 moved(dvec3(p) - (f / g2) * grad);
    const dvec3 q2 = gridPoint(*this, moved) - dvec3(v);
    const bool inside = glm::all(glm::greaterThanEqual(q2, dvec3(0.0))) && glm::all(glm::lessThanEqual(q2, dvec3(1.0)));
    return inside && std::abs(trilinear(s, q2)) < std::abs(f) ? moved : p;
}

// The smooth shading normal of Hansson-Söderlund, Evans & Akenine-Möller (2022, JCGT 11(3),
// as Mitsuba 3's sdfgrid computes it): the normalised gradients of the 8 voxels around the grid
// sample nearest to p, blended trilinearly by p's position between those voxels' centres. Each
// voxel's gradient along axis a is the difference of the interpolant across the voxel's extent
// along a, taken at p's coordinates along the other two axes (bilinear in the cell containing p),
// so the blend is continuous across voxel faces and the normal varies smoothly over the surface.
// Voxels outside the grid get weight 0. The gradients are normalised and blended in the shape's
// space (Mitsuba 3: in object space, then carried to world).
vec3 SdfGrid::shadingNormal(uint32_t prim, const vec3& p) const {
    if (!smoothNormals) return analyticNormal(prim, p);
    const dvec3 P = gridPoint(*this, p);
    const ivec3 cell = glm::clamp(ivec3(glm::floor(P)), ivec3(0), res - 2);
    const dvec3 w = glm::clamp(P - dvec3(cell), 0.0, 1.0);
    const ivec3 nearest = glm::clamp(ivec3(glm::round(P)), ivec3(0), res - 1);
    // The interpolant on the grid plane with index k along axis a, at p's position along the others.
    auto plane = [&](int a, int k) {
        const int b = (a + 1) % 3, e = (a + 2) % 3;
        double f[4];
        for (int i = 0; i < 4; ++i) {
            ivec3 idx;
            idx[a] = std::clamp(k, 0, res[a] - 1);
            idx[b] = cell[b] + (i & 1);
            idx[e] = cell[e] + (i >> 1);
            f[i] = at(idx.x, idx.y, idx.z);
        }
        return lerpExact(lerpExact(f[0], f[1], w[b]), lerpExact(f[2], f[3], w[b]), w[e]);
    };
    dvec3 lower(0.0), upper(0.0), tUpper(0.0);  // per axis: the two voxels' differences, and the upper one's weight
    for (int a = 0; a < 3; ++a) {
        const int q = nearest[a] - 1;  // the lower voxel's index along a; the upper one is q + 1
        lower[a] = plane(a, q + 1) - plane(a, q);
        upper[a] = plane(a, q + 2) - plane(a, q + 1);
        tUpper[a] = q < 0 ? 1.0 : q + 1 > res[a] - 2 ? 0.0 : std::clamp(P[a] - double(q) - 0.5, 0.0, 1.0);
    }
    dvec3 n(0.0);
    for (int c = 0; c < 8; ++c) {
        double weight = 1;
        dvec3 grad;
        for (int a = 0; a < 3; ++a) {
            const bool up = (c >> a) & 1;
            weight *= up ? tUpper[a] : 1.0 - tUpper[a];
            grad[a] = up ? upper[a] : lower[a];
        }
        const dvec3 shape = toShapeGradient(*this, grad);
        const double len = glm::length(shape);
        if (weight > 0 && len > 0) n += weight * shape / len;
    }
    return unitOr(n, analyticNormal(prim, p));
}

}  // namespace iris
