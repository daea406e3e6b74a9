// A coarse grid of majorants over a volume's world box, and its traversal along a ray
// (pbrt-v4 §11.4.3 "MajorantGrid" and DDAMajorantIterator; the digital differential analyser of
// Amanatides & Woo 1987, "A Fast Voxel Traversal Algorithm for Ray Tracing").
//
// The cells split the volume's world box (Volume::bounds) evenly. Each holds an upper bound of the
// volume over every point of the cell: Volume::maxValueIn over the local-space box of the cell's
// 8 corners mapped by to_world⁻¹ (conservative for any affine to_world; the grid's own bound takes
// both trilinear neighbours into account), the cell first padded by kCellPad of its size so that
// rounding of the segment ends can never leave a point outside the cell whose bound it gets.
// Distances t are world distances along the ray as given (scene units per unit of t: the volume is
// a field of world points, so a scaling to_world changes where its values are, not their units).
#pragma once

#include <vector>

#include "core/arena.h"
#include "core/ray.h"
#include "media/medium.h"
#include "media/volumes/volume.h"

namespace iris {

class MajorantGrid {
public:
    /// Cells per axis of a grid over a volume: 16, or fewer along an axis the volume has fewer
    /// voxels on when to_world keeps the axes (no rotation or shear).
    static constexpr int kMaxResolution = 16;
    /// Padding of each cell on every side, as a fraction of its size.
    static constexpr float kCellPad = 1e-3f;

    /// The resolution kMaxResolution describes for this volume.
    static ivec3 resolutionFor(const Volume& v);

    MajorantGrid(const Volume& v, ivec3 res);

    const Box3& bounds() const { return box_; }
    ivec3 resolution() const { return res_; }
    /// The bound of cell (x, y, z) (before any scale).
    float cell(int x, int y, int z) const { return cells_[(size_t(z) * res_.y + y) * res_.x + x]; }

    /// The segments of the ray over [0, tMax) inside the box, one per cell it crosses in order,
    /// σ_maj = scale · the cell's bound in each of nLanes lanes; cells whose bound is 0 are left
    /// out (gaps where σ_t = 0). The iterator lives in the arena and refers to this grid.
    MajorantIterator* traverse(const Ray& ray, float tMax, float scale, int nLanes, Arena& arena) const;

private:
    friend class DDAMajorantIterator;
    Box3 box_;
    ivec3 res_;
    vec3 cellSize_;
    std::vector<float> cells_;  // (z·res.y + y)·res.x + x
};

/// The DDA over a MajorantGrid (trivially destructible: lives in the Arena).
class DDAMajorantIterator final : public MajorantIterator {
public:
    /// The cells of `grid` crossed by the ray over [t0, t1] (the ray's piece inside the box).
    DDAMajorantIterator(const MajorantGrid& grid, const Ray& ray, float t0, float t1, float scale, int nLanes);
    /// An iterator with no segments.
    DDAMajorantIterator() = default;
    std::optional<MajorantSegment> next() override;

private:
    const float* cells_ = nullptr;
    int res_[3] = {0, 0, 0}, cell_[3] = {0, 0, 0}, step_[3] = {0, 0, 0};
    float tNext_[3] = {0, 0, 0}, tDelta_[3] = {0, 0, 0};
    float t_ = 0.0f, tEnd_ = 0.0f, scale_ = 0.0f;
    int nLanes_ = 0;
    bool done_ = true;
};

}  // namespace iris
