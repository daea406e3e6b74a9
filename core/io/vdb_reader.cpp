#include "core/io/vdb_reader.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <memory>

#include "core/error.h"
#include "core/io/vdb_loader.h"
#include "core/memory_budget.h"

namespace iris {
namespace {

/// Dense values a grid may have (2^40, as .vol files): a bound on the product of the box's sides
/// before it is charged, so that it cannot overflow.
constexpr uint64_t kMaxValues = uint64_t(1) << 40;

/// Room for the module's messages; the longest, a wrong grid name with the file's grid list, is
/// cut there.
constexpr size_t kErrorBytes = 4096;

/// The file's size against the memory budget, before OpenVDB reads it.
void checkFileSize(const std::string& path) {
    std::error_code ec;
    const uintmax_t size = std::filesystem::file_size(path, ec);
    if (ec) fail(path, ": cannot open the OpenVDB file (", ec.message(), ")");
    checkMemory(size, strCat(path, ": the OpenVDB file"));
}

/// The dense grid's size, charged to the memory budget, then allocated.
VolumeGridData denseShape(const iris_vdb_info& info, const std::string& path) {
    const std::string name = info.grid_name;
    const int* dim = info.dims;
    uint64_t n = uint64_t(info.channels);
    for (int a = 0; a < 3; ++a) {
        if (dim[a] <= 0 || n > kMaxValues / uint64_t(dim[a]))
            fail(path, ": grid '", name, "' spans ", dim[0], "x", dim[1], "x", dim[2], " voxels, too many to densify (over 2^40 values)");
        n *= uint64_t(dim[a]);
    }
    chargeMemory(n * sizeof(float), strCat(path, ": grid '", name, "' densified to ", dim[0], "x", dim[1], "x", dim[2], "x",
                                           info.channels, " floats"));
    VolumeGridData g;
    g.xres = dim[0], g.yres = dim[1], g.zres = dim[2], g.channels = info.channels;
    g.bboxMin = vec3(info.bbox_min[0], info.bbox_min[1], info.bbox_min[2]);
    g.bboxMax = vec3(info.bbox_max[0], info.bbox_max[1], info.bbox_max[2]);
    g.values.resize(size_t(n));
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
    checkFileSize(path);
    const VdbModule& vdb = vdbModule(path, "read the OpenVDB file");
    char err[kErrorBytes] = "";
    iris_vdb_info info{};
    // The module keeps the grid read until close; the dense floats are charged and allocated
    // here, between its two calls.
    const std::unique_ptr<void, iris_vdb_close_fn> grid(vdb.open(path.c_str(), gridName.c_str(), &info, err, sizeof err),
                                                        vdb.close);
    if (!grid) fail(path, ": ", err);
    VolumeGridData g = denseShape(info, path);
    if (!vdb.readDense(grid.get(), g.values.data(), g.values.size(), err, sizeof err)) fail(path, ": ", err);
    return g;
}

}  // namespace iris
