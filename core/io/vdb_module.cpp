// The OpenVDB module (libiris_vdb.so): the only code linked to OpenVDB. Built as a CMake MODULE
// (not part of the `iris` library) and loaded on demand by core/io/vdb_loader.cpp; the interface
// is the C ABI in core/io/vdb_module.h, the rules it implements are core/io/vdb_reader.h's. No
// exception leaves these functions.
#include "core/io/vdb_module.h"

// OpenVDB's headers are not written for -fvisibility=hidden: with it, the module's inline code
// (Grid::gridType reading Tree's static type name, OpenVDB 10) uses hidden copies of statics that
// libopenvdb initialises in its own copies, and crashes. Its declarations keep default visibility;
// the module's own code stays hidden (only the iris_vdb_* functions are exported for it).
#pragma GCC visibility push(default)
#include <openvdb/openvdb.h>
#pragma GCC visibility pop

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <limits>
#include <memory>
#include <mutex>
#include <string>
#include <type_traits>

// Only strCat/fail/Error (header-only): the module does not link the iris library. With hidden
// visibility its copy of iris::Error stays private to it, and is caught here.
#include "core/error.h"

#define IRIS_VDB_EXPORT extern "C" __attribute__((visibility("default")))

namespace {

using iris::fail;

/// A grid read by iris_vdb_open.
struct OpenGrid {
    openvdb::GridBase::Ptr grid;
    std::string name;
    openvdb::CoordBBox box;  // active voxels, index space, inclusive
};

void setError(char* err, size_t errlen, const std::string& msg) {
    if (!err || errlen == 0) return;
    std::snprintf(err, errlen, "%s", msg.c_str());
}

/// fn() across the C boundary: an iris::Error's message, or "<what> (<message>)" for any other
/// exception (OpenVDB's IoError and the like, the streams' errors), goes to err and `failed` is
/// returned.
template <typename R, typename Fn>
R guarded(char* err, size_t errlen, const char* what, R failed, Fn&& fn) {
    try {
        return fn();
    } catch (const iris::Error& e) {
        setError(err, errlen, e.what());
    } catch (const std::exception& e) {
        setError(err, errlen, iris::strCat(what, " (", e.what(), ")"));
    } catch (...) {
        setError(err, errlen, iris::strCat(what, " (unknown error)"));
    }
    return failed;
}

void initializeOpenVdb() {
    static std::once_flag once;
    std::call_once(once, [] { openvdb::initialize(); });
}

std::string gridNames(const openvdb::io::File& file) {
    std::string names;
    for (auto it = file.beginName(); it != file.endName(); ++it) names += (names.empty() ? "" : ", ") + *it;
    return names.empty() ? "none" : names;
}

/// The grid to read: `name`, or the only one of the file.
std::string chooseGrid(const openvdb::io::File& file, const std::string& name) {
    if (!name.empty()) {
        if (!file.hasGrid(name)) fail("no grid named '", name, "' (grids in the file: ", gridNames(file), ")");
        return name;
    }
    size_t count = 0;
    for (auto it = file.beginName(); it != file.endName(); ++it) ++count;
    if (count != 1)
        fail("the file holds ", count, " grids (", gridNames(file), "): name one with <string name=\"grid\" value=\"...\"/>");
    return *file.beginName();
}

openvdb::GridBase::Ptr readGrid(const std::string& path, const std::string& name) {
    openvdb::io::File file(path);
    file.open(false);  // no delayed loading: the grid is read now, not mapped
    openvdb::GridBase::Ptr grid = file.readGrid(chooseGrid(file, name));
    file.close();
    return grid;
}

/// 1 or 3 for the value types read, 0 for the others.
int channelCount(const openvdb::GridBase& grid) {
    if (grid.isType<openvdb::FloatGrid>() || grid.isType<openvdb::DoubleGrid>()) return 1;
    if (grid.isType<openvdb::Vec3SGrid>() || grid.isType<openvdb::Vec3DGrid>()) return 3;
    return 0;
}

/// The world box of the index box [lo − ½, hi + ½] under the grid's transform (its 8 corners'
/// bounds, each corner rounded to float first).
void worldBox(const openvdb::GridBase& grid, const openvdb::CoordBBox& box, iris_vdb_info& info) {
    for (int a = 0; a < 3; ++a) {
        info.bbox_min[a] = std::numeric_limits<float>::infinity();
        info.bbox_max[a] = -std::numeric_limits<float>::infinity();
    }
    for (int c = 0; c < 8; ++c) {
        const openvdb::Vec3d corner((c & 1 ? box.max().x() + 0.5 : box.min().x() - 0.5), (c & 2 ? box.max().y() + 0.5 : box.min().y() - 0.5),
                                    (c & 4 ? box.max().z() + 0.5 : box.min().z() - 0.5));
        const openvdb::Vec3d w = grid.indexToWorld(corner);
        for (int a = 0; a < 3; ++a) {
            info.bbox_min[a] = std::min(info.bbox_min[a], float(w[a]));
            info.bbox_max[a] = std::max(info.bbox_max[a], float(w[a]));
        }
    }
}

/// The open grid with its shape in `info`; refuses other value types and empty grids.
std::unique_ptr<OpenGrid> openGrid(const std::string& path, const std::string& name, iris_vdb_info& info) {
    auto g = std::make_unique<OpenGrid>();
    try {
        g->grid = readGrid(path, name);
    } catch (const iris::Error&) {
        throw;
    } catch (const std::exception& e) {
        fail("cannot read the OpenVDB file (", e.what(), ")");
    }
    g->name = g->grid->getName();
    info.channels = channelCount(*g->grid);
    if (info.channels == 0)
        fail("grid '", g->name, "' holds values of type ", g->grid->valueType(), " (supported: float, double, vec3s, vec3d)");
    g->box = g->grid->evalActiveVoxelBoundingBox();
    if (g->grid->activeVoxelCount() == 0 || g->box.empty()) fail("grid '", g->name, "' has no active voxels");
    const openvdb::Coord dim = g->box.dim();
    for (int a = 0; a < 3; ++a) info.dims[a] = dim[a];
    worldBox(*g->grid, g->box, info);
    info.grid_name = g->name.c_str();
    return g;
}

float checked(double v, const openvdb::Coord& ijk, const std::string& name) {
    if (!std::isfinite(v) || std::abs(v) > double(std::numeric_limits<float>::max()))
        fail("grid '", name, "' has a non-finite value (", v, ") at voxel (", ijk.x(), ", ", ijk.y(), ", ", ijk.z(), ")");
    return float(v);
}

/// Every voxel of the active box, through a value accessor (inactive ones give the background),
/// x fastest.
template <class GridT>
void densify(const GridT& grid, const OpenGrid& g, float* out) {
    const openvdb::Coord lo = g.box.min(), dim = g.box.dim();
    auto acc = grid.getConstAccessor();
    for (int z = 0; z < dim.z(); ++z)
        for (int y = 0; y < dim.y(); ++y)
            for (int x = 0; x < dim.x(); ++x) {
                const openvdb::Coord ijk = lo + openvdb::Coord(x, y, z);
                const auto v = acc.getValue(ijk);
                if constexpr (std::is_floating_point_v<decltype(v)>) *out++ = checked(double(v), ijk, g.name);
                else
                    for (int c = 0; c < 3; ++c) *out++ = checked(double(v[c]), ijk, g.name);
            }
}

size_t denseCount(const OpenGrid& g) {
    const openvdb::Coord dim = g.box.dim();
    return size_t(dim.x()) * size_t(dim.y()) * size_t(dim.z()) * size_t(channelCount(*g.grid));
}

}  // namespace

IRIS_VDB_EXPORT int iris_vdb_abi_version(void) { return IRIS_VDB_ABI_VERSION; }

IRIS_VDB_EXPORT void* iris_vdb_open(const char* path, const char* grid_name, iris_vdb_info* info, char* err, size_t errlen) {
    return guarded(err, errlen, "cannot read the OpenVDB file", static_cast<void*>(nullptr), [&]() -> void* {
        initializeOpenVdb();
        *info = iris_vdb_info{};
        return openGrid(path, grid_name ? grid_name : "", *info).release();
    });
}

IRIS_VDB_EXPORT int iris_vdb_read_dense(void* handle, float* out, size_t count, char* err, size_t errlen) {
    return guarded(err, errlen, "cannot read the OpenVDB grid", 0, [&] {
        const auto& g = *static_cast<const OpenGrid*>(handle);
        if (count != denseCount(g)) fail("the buffer holds ", count, " floats, the grid ", denseCount(g));
        if (auto f = openvdb::GridBase::grid<openvdb::FloatGrid>(g.grid)) densify(*f, g, out);
        else if (auto d = openvdb::GridBase::grid<openvdb::DoubleGrid>(g.grid)) densify(*d, g, out);
        else if (auto v = openvdb::GridBase::grid<openvdb::Vec3SGrid>(g.grid)) densify(*v, g, out);
        else if (auto w = openvdb::GridBase::grid<openvdb::Vec3DGrid>(g.grid)) densify(*w, g, out);
        return 1;
    });
}

IRIS_VDB_EXPORT void iris_vdb_close(void* handle) { delete static_cast<OpenGrid*>(handle); }
