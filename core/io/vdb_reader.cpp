#include "core/io/vdb_reader.h"

#include <openvdb/openvdb.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <limits>
#include <mutex>

#include "core/error.h"
#include "core/memory_budget.h"

namespace iris {
namespace {

/// Dense values a grid may have (2^40, as .vol files): a bound on the product of the box's sides
/// before it is charged, so that it cannot overflow.
constexpr uint64_t kMaxValues = uint64_t(1) << 40;

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
std::string chooseGrid(const openvdb::io::File& file, const std::string& name, const std::string& path) {
    if (!name.empty()) {
        if (!file.hasGrid(name)) fail(path, ": no grid named '", name, "' (grids in the file: ", gridNames(file), ")");
        return name;
    }
    size_t count = 0;
    for (auto it = file.beginName(); it != file.endName(); ++it) ++count;
    if (count != 1)
        fail(path, ": the file holds ", count, " grids (", gridNames(file), "): name one with <string name=\"grid\" value=\"...\"/>");
    return *file.beginName();
}

openvdb::GridBase::Ptr readGrid(const std::string& path, const std::string& name) {
    std::error_code ec;
    const uintmax_t size = std::filesystem::file_size(path, ec);
    if (ec) fail(path, ": cannot open the OpenVDB file (", ec.message(), ")");
    checkMemory(size, strCat(path, ": the OpenVDB file"));
    try {
        openvdb::io::File file(path);
        file.open(false);  // no delayed loading: the grid is read now, not mapped
        openvdb::GridBase::Ptr grid = file.readGrid(chooseGrid(file, name, path));
        file.close();
        return grid;
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {  // openvdb::Exception (IoError, ...) and the streams' errors
        fail(path, ": cannot read the OpenVDB file (", e.what(), ")");
    }
}

/// The world box of the index box [lo − ½, hi + ½] under the grid's transform.
void worldBox(const openvdb::GridBase& grid, const openvdb::CoordBBox& box, VolumeGridData& g) {
    g.bboxMin = vec3(std::numeric_limits<float>::infinity());
    g.bboxMax = -g.bboxMin;
    for (int c = 0; c < 8; ++c) {
        const openvdb::Vec3d corner((c & 1 ? box.max().x() + 0.5 : box.min().x() - 0.5), (c & 2 ? box.max().y() + 0.5 : box.min().y() - 0.5),
                                    (c & 4 ? box.max().z() + 0.5 : box.min().z() - 0.5));
        const openvdb::Vec3d w = grid.indexToWorld(corner);
        const vec3 p(float(w.x()), float(w.y()), float(w.z()));
        g.bboxMin = glm::min(g.bboxMin, p);
        g.bboxMax = glm::max(g.bboxMax, p);
    }
}

/// The dense grid's size, charged to the memory budget before anything is allocated.
VolumeGridData denseShape(const openvdb::GridBase& grid, int channels, const std::string& path, const std::string& name) {
    const openvdb::CoordBBox box = grid.evalActiveVoxelBoundingBox();
    if (grid.activeVoxelCount() == 0 || box.empty()) fail(path, ": grid '", name, "' has no active voxels");
    const openvdb::Coord dim = box.dim();
    uint64_t n = uint64_t(channels);
    for (int a = 0; a < 3; ++a) {
        if (dim[a] <= 0 || n > kMaxValues / uint64_t(dim[a]))
            fail(path, ": grid '", name, "' spans ", dim.x(), "x", dim.y(), "x", dim.z(), " voxels, too many to densify (over 2^40 values)");
        n *= uint64_t(dim[a]);
    }
    chargeMemory(n * sizeof(float), strCat(path, ": grid '", name, "' densified to ", dim.x(), "x", dim.y(), "x", dim.z(), "x",
                                           channels, " floats"));
    VolumeGridData g;
    g.xres = dim.x(), g.yres = dim.y(), g.zres = dim.z(), g.channels = channels;
    worldBox(grid, box, g);
    g.values.resize(size_t(n));
    return g;
}

float checked(double v, const openvdb::Coord& ijk, const std::string& path, const std::string& name) {
    if (!std::isfinite(v) || std::abs(v) > double(std::numeric_limits<float>::max()))
        fail(path, ": grid '", name, "' has a non-finite value (", v, ") at voxel (", ijk.x(), ", ", ijk.y(), ", ", ijk.z(), ")");
    return float(v);
}

/// Every voxel of the active box, through a value accessor (inactive ones give the background).
template <class GridT, int Channels>
VolumeGridData densify(const GridT& grid, const std::string& path, const std::string& name) {
    VolumeGridData g = denseShape(grid, Channels, path, name);
    const openvdb::Coord lo = grid.evalActiveVoxelBoundingBox().min();
    auto acc = grid.getConstAccessor();
    for (int z = 0; z < g.zres; ++z)
        for (int y = 0; y < g.yres; ++y)
            for (int x = 0; x < g.xres; ++x) {
                const openvdb::Coord ijk = lo + openvdb::Coord(x, y, z);
                const auto v = acc.getValue(ijk);
                if constexpr (Channels == 1) g.values[g.index(x, y, z, 0)] = checked(double(v), ijk, path, name);
                else
                    for (int c = 0; c < 3; ++c) g.values[g.index(x, y, z, c)] = checked(double(v[c]), ijk, path, name);
            }
    return g;
}

}  // namespace

bool isVdbFileName(const std::string& path) {
    if (path.size() < 4) return false;
    std::string ext = path.substr(path.size() - 4);
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext == ".vdb";
}

VolumeGridData readVdbFile(const std::string& path, const std::string& gridName) {
    initializeOpenVdb();
    const openvdb::GridBase::Ptr grid = readGrid(path, gridName);
    const std::string name = grid->getName();
    if (auto f = openvdb::GridBase::grid<openvdb::FloatGrid>(grid)) return densify<openvdb::FloatGrid, 1>(*f, path, name);
    if (auto d = openvdb::GridBase::grid<openvdb::DoubleGrid>(grid)) return densify<openvdb::DoubleGrid, 1>(*d, path, name);
    if (auto v = openvdb::GridBase::grid<openvdb::Vec3SGrid>(grid)) return densify<openvdb::Vec3SGrid, 3>(*v, path, name);
    if (auto v = openvdb::GridBase::grid<openvdb::Vec3DGrid>(grid)) return densify<openvdb::Vec3DGrid, 3>(*v, path, name);
    fail(path, ": grid '", name, "' holds values of type ", grid->valueType(), " (supported: float, double, vec3s, vec3d)");
}

}  // namespace iris
