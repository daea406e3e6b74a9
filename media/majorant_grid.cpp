#include "media/majorant_grid.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace iris {

ivec3 MajorantGrid::resolutionFor(const Volume& v) {
    const mat3 m(v.toWorld());
    bool axisAligned = true;  // the linear part is diagonal: world axis a is local axis a
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) axisAligned = axisAligned && (r == c || m[c][r] == 0.0f);
    if (!axisAligned) return ivec3(kMaxResolution);
    return glm::clamp(v.resolution(), ivec3(1), ivec3(kMaxResolution));
}

MajorantGrid::MajorantGrid(const Volume& v, ivec3 res) : box_(v.bounds()), res_(res) {
    cellSize_ = (box_.hi - box_.lo) / vec3(res_);
    cells_.resize(size_t(res_.x) * res_.y * res_.z);
    for (int z = 0; z < res_.z; ++z)
        for (int y = 0; y < res_.y; ++y)
            for (int x = 0; x < res_.x; ++x) {
                const vec3 lo = box_.lo + vec3(x, y, z) * cellSize_, pad = kCellPad * cellSize_;
                const Box3 world{lo - pad, lo + cellSize_ + pad};
                cells_[(size_t(z) * res_.y + y) * res_.x + x] = v.maxValueIn(transformBox(v.toLocal(), world));
            }
}

MajorantIterator* MajorantGrid::traverse(const Ray& ray, float tMax, float scale, int nLanes, Arena& arena) const {
    float t0 = 0.0f, t1 = 0.0f;
    if (box_.degenerate() || !box_.clip(ray, tMax, t0, t1) || !(t1 > t0)) return arena.make<DDAMajorantIterator>();
    return arena.make<DDAMajorantIterator>(*this, ray, t0, t1, scale, nLanes);
}

DDAMajorantIterator::DDAMajorantIterator(const MajorantGrid& grid, const Ray& ray, float t0, float t1, float scale,
                                         int nLanes)
    : cells_(grid.cells_.data()), t_(t0), tEnd_(t1), scale_(scale), nLanes_(nLanes), done_(false) {
    // Amanatides & Woo 1987 §3: the cell of the entry point, and per axis the t of the next cell
    // boundary (tMax there) and the t between two boundaries (tDelta).
    const vec3 entry = (ray.at(t0) - grid.box_.lo) / grid.cellSize_;
    for (int a = 0; a < 3; ++a) {
        res_[a] = grid.res_[a];
        cell_[a] = std::clamp(int(std::floor(entry[a])), 0, res_[a] - 1);
        if (ray.d[a] == 0.0f) {
            tNext_[a] = std::numeric_limits<float>::infinity();
            continue;
        }
        step_[a] = ray.d[a] > 0 ? 1 : -1;
        const float plane = grid.box_.lo[a] + float(cell_[a] + (step_[a] > 0 ? 1 : 0)) * grid.cellSize_[a];
        tNext_[a] = (plane - ray.o[a]) / ray.d[a];
        tDelta_[a] = grid.cellSize_[a] / std::abs(ray.d[a]);
    }
}

std::optional<MajorantSegment> DDAMajorantIterator::next() {
    while (!done_) {
        // The axis whose boundary comes first (Amanatides & Woo 1987, the loop of §3).
        const int a = tNext_[0] < tNext_[1] ? (tNext_[0] < tNext_[2] ? 0 : 2) : (tNext_[1] < tNext_[2] ? 1 : 2);
        const float bound = cells_[(size_t(cell_[2]) * res_[1] + cell_[1]) * res_[0] + cell_[0]];
        const bool leaves = cell_[a] + step_[a] < 0 || cell_[a] + step_[a] >= res_[a];
        // The last cell takes the rest of [t0, t1]: rounding cannot lose a piece inside the box.
        const float start = t_, end = std::max(start, leaves ? tEnd_ : std::min(tNext_[a], tEnd_));
        t_ = end;
        if (leaves || end >= tEnd_) {
            done_ = true;
        } else {
            cell_[a] += step_[a];
            tNext_[a] += tDelta_[a];
        }
        if (bound > 0.0f && end > start) return MajorantSegment{start, end, SampledSpectrum(nLanes_, scale_ * bound)};
    }
    return std::nullopt;
}

}  // namespace iris
