// OpenVDB grids in gridvolume (core/io/vdb_reader.cpp, media/volumes/gridvolume.cpp): a .vdb
// written here with the OpenVDB API evaluates exactly as the same data written as a .vol (scalar
// and vec3 grids, the file's box through use_grid_bbox, inactive voxels as the background) and
// renders bit-identically in a heterogeneous medium; a missing grid, an ambiguous file, an
// unsupported grid type and a grid too large to densify give errors with the scene line.
#include <gtest/gtest.h>

#include <openvdb/openvdb.h>

#include <filesystem>
#include <fstream>

#include "core/io/vdb_reader.h"
#include "core/memory_budget.h"
#include "core/rng.h"
#include "media/volumes/volume.h"
#include "tests/support/error_of.h"
#include "tests/support/image_mean.h"
#include "tests/support/vol_file.h"

using namespace iris;
using namespace iris::test;

namespace {

std::string tempPath(const std::string& name) {
    const auto dir = std::filesystem::temp_directory_path() /
                     ("iris_vdb_volume_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    std::filesystem::create_directories(dir);
    return (dir / name).string();
}

void writeVdb(const std::string& path, const openvdb::GridPtrVec& grids) {
    openvdb::initialize();
    openvdb::io::File(path).write(grids);
}

/// Voxels of size 0.25, offset by (1, 2, 3).
openvdb::math::Transform::Ptr voxelTransform() {
    auto transform = openvdb::math::Transform::createLinearTransform(0.25);
    transform->postTranslate(openvdb::Vec3d(1, 2, 3));
    return transform;
}

/// A float grid named `name` over voxels lo + [0, dim) of value v(i, j, k) (voxels where v is 0
/// are left inactive: they read as the background 0), placed by voxelTransform.
template <class F>
openvdb::FloatGrid::Ptr floatGrid(const std::string& name, const openvdb::Coord& lo, const ivec3& dim, F&& v) {
    auto grid = openvdb::FloatGrid::create(0.0f);
    grid->setName(name);
    grid->setTransform(voxelTransform());
    auto acc = grid->getAccessor();
    for (int k = 0; k < dim.z; ++k)
        for (int j = 0; j < dim.y; ++j)
            for (int i = 0; i < dim.x; ++i)
                if (const float value = v(i, j, k); value != 0) acc.setValue(lo + openvdb::Coord(i, j, k), value);
    return grid;
}

const ivec3 kDim(5, 4, 3);
const openvdb::Coord kLo(-2, 7, 1);
float density(int i, int j, int k) { return (i + 2 * j + 3 * k) % 4 == 0 ? 0.0f : 0.5f + float(i) + 0.25f * float(j * k); }

/// The same values as a .vol, with the world box the .vdb's transform gives its voxels:
/// index box [lo − ½, lo + dim − ½] · 0.25 + (1, 2, 3).
std::string sameAsVol(int channels, const std::vector<float>& values) {
    const vec3 lo = (vec3(kLo.x(), kLo.y(), kLo.z()) - 0.5f) * 0.25f + vec3(1, 2, 3);
    return writeVolFile("iris_vdb_volume", channels == 1 ? "same.vol" : "same3.vol", kDim, channels, values, lo, lo + vec3(kDim) * 0.25f);
}

std::vector<float> denseDensity() {
    std::vector<float> v;
    for (int k = 0; k < kDim.z; ++k)
        for (int j = 0; j < kDim.y; ++j)
            for (int i = 0; i < kDim.x; ++i) v.push_back(density(i, j, k));
    return v;
}

std::shared_ptr<Properties> gridProps(const std::string& file, bool useBox, const std::string& grid = "") {
    auto p = std::make_shared<Properties>("volume", "gridvolume", SourceLocation{"scene.xml", 5});
    p->set("filename", file, SourceLocation{"scene.xml", 6});
    if (!grid.empty()) p->set("grid", grid, SourceLocation{"scene.xml", 7});
    p->set("use_grid_bbox", useBox, SourceLocation{"scene.xml", 8});
    return p;
}

VolumePtr makeGrid(const std::string& file, bool useBox, const std::string& grid = "") {
    return VolumeRegistry::instance().create(*gridProps(file, useBox, grid), SpectrumKind::Unbounded);
}

/// The largest difference of two volumes' values over random points of the box [lo, hi].
float largestDifference(const Volume& a, const Volume& b, const vec3& lo, const vec3& hi) {
    const SampledWavelengths rgb = SampledWavelengths::rgb(defaultChannelWavelengths());
    Pcg32 rng(4, 2);
    float worst = 0;
    for (int i = 0; i < 2000; ++i) {
        const vec3 p = lo + (hi - lo) * vec3(rng.uniform(), rng.uniform(), rng.uniform());
        const SampledSpectrum va = a.eval(p, rgb), vb = b.eval(p, rgb);
        for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(va[c] - vb[c]));
    }
    return worst;
}

struct MemoryLimit {
    uint64_t previous = memoryLimit();
    explicit MemoryLimit(uint64_t bytes) { setMemoryLimit(bytes); }
    ~MemoryLimit() { setMemoryLimit(previous); }
};

}  // namespace

TEST(VdbVolume, EvaluatesAsTheSameDataWrittenAsVol) {
    const std::string vdb = tempPath("smoke.vdb");
    writeVdb(vdb, {floatGrid("density", kLo, kDim, density)});
    const std::string vol = sameAsVol(1, denseDensity());
    // In the unit cube (to_world identity) and in the file's own box (use_grid_bbox).
    EXPECT_EQ(largestDifference(*makeGrid(vdb, false, "density"), *makeGrid(vol, false), vec3(-0.2f), vec3(1.2f)), 0.0f);
    const VolumePtr boxed = makeGrid(vdb, true);  // the file's only grid needs no name
    EXPECT_EQ(largestDifference(*boxed, *makeGrid(vol, true), boxed->bounds().lo, boxed->bounds().hi), 0.0f);
    EXPECT_GT(largestDifference(*boxed, *makeGrid(vol, false), boxed->bounds().lo, boxed->bounds().hi), 0.1f);  // can fail
    // A vec3 grid: 3 channels, read as RGB.
    auto colour = openvdb::Vec3SGrid::create(openvdb::Vec3s(0.0f));
    colour->setName("albedo");
    colour->setTransform(voxelTransform());
    std::vector<float> rgb;
    auto acc = colour->getAccessor();
    for (int k = 0; k < kDim.z; ++k)
        for (int j = 0; j < kDim.y; ++j)
            for (int i = 0; i < kDim.x; ++i) {
                const openvdb::Vec3s c(0.1f * float(i), 0.2f * float(j), 0.3f * float(k) + 0.05f);
                acc.setValue(kLo + openvdb::Coord(i, j, k), c);
                rgb.insert(rgb.end(), {c.x(), c.y(), c.z()});
            }
    const std::string vdb3 = tempPath("colour.vdb");
    writeVdb(vdb3, {colour});
    EXPECT_EQ(largestDifference(*makeGrid(vdb3, false, "albedo"), *makeGrid(sameAsVol(3, rgb), false), vec3(0.0f), vec3(1.0f)), 0.0f);
}

TEST(VdbVolume, RendersAsTheSameDataWrittenAsVol) {
    const std::string vdb = tempPath("smoke.vdb");
    writeVdb(vdb, {floatGrid("density", kLo, kDim, density)});
    const std::string vol = sameAsVol(1, denseDensity());
    auto render = [](const std::string& file, const std::string& grid) {
        return renderXml("<scene version=\"3.0.0\">\n<medium type=\"heterogeneous\" id=\"m\"><volume type=\"gridvolume\" name=\"sigma_t\">"
                         "<string name=\"filename\" value=\"" + file + "\"/>" + grid +
                         "<transform name=\"to_world\"><translate value=\"-0.5, -0.5, -0.5\"/></transform></volume>"
                         "<float name=\"scale\" value=\"3\"/></medium>\n"
                         "<shape type=\"cube\"><bsdf type=\"null\"/><ref name=\"interior\" id=\"m\"/>"
                         "<transform name=\"to_world\"><scale value=\"0.5\"/></transform></shape>\n"
                         "<emitter type=\"constant\"><rgb name=\"radiance\" value=\"1, 1, 1\"/></emitter>\n"
                         "<sensor type=\"perspective\"><transform name=\"to_world\"><lookat origin=\"0.3, 0.2, -3\" target=\"0, 0, 0\" "
                         "up=\"0, 1, 0\"/></transform><film type=\"hdrfilm\"><integer name=\"width\" value=\"16\"/>"
                         "<integer name=\"height\" value=\"16\"/></film></sensor>\n<integrator type=\"volpathmis\"/>\n</scene>\n",
                         16, 16, 4, 11, false);
    };
    const Film a = render(vdb, "<string name=\"grid\" value=\"density\"/>"), b = render(vol, "");
    bool equal = true, some = false;
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x) equal &= a.pixel(x, y) == b.pixel(x, y), some |= a.pixel(x, y).y < 0.99f;
    EXPECT_TRUE(equal);
    EXPECT_TRUE(some);  // the medium is seen: it darkens some pixels
}

TEST(VdbVolume, BadFilesAndGridsGiveTheSceneLine) {
    const std::string two = tempPath("two.vdb");
    writeVdb(two, {floatGrid("density", kLo, kDim, density), floatGrid("temperature", kLo, kDim, density)});
    EXPECT_TRUE(contains(errorOf([&] { makeGrid(two, false, "smoke"); }),
                         "scene.xml:6: " + two + ": no grid named 'smoke' (grids in the file: density, temperature)"));
    EXPECT_TRUE(contains(errorOf([&] { makeGrid(two, false); }), "scene.xml:6: " + two + ": the file holds 2 grids (density, temperature)"));
    EXPECT_EQ(errorOf([&] { makeGrid(two, false, "temperature"); }), "");
    auto ints = openvdb::Int32Grid::create(0);
    ints->setName("labels");
    ints->getAccessor().setValue(openvdb::Coord(0), 3);
    const std::string labels = tempPath("labels.vdb");
    writeVdb(labels, {ints});
    EXPECT_TRUE(contains(errorOf([&] { makeGrid(labels, false); }), "grid 'labels' holds values of type int32 (supported: float, double, vec3s, vec3d)"));
    EXPECT_TRUE(contains(errorOf([&] { makeGrid(tempPath("missing.vdb"), false); }), "scene.xml:6: " + tempPath("missing.vdb") + ": cannot open"));
    const std::string notVdb = tempPath("text.vdb");
    std::ofstream(notVdb) << "not a vdb file";
    EXPECT_TRUE(contains(errorOf([&] { makeGrid(notVdb, false); }), "scene.xml:6: " + notVdb + ": cannot read the OpenVDB file"));
    // 'grid' belongs to .vdb files.
    EXPECT_TRUE(contains(errorOf([&] { makeGrid(sameAsVol(1, denseDensity()), false, "density"); }), "scene.xml:7: gridvolume: 'grid' names a grid of a .vdb file"));
}

TEST(VdbVolume, GridsTooLargeToDensifyAreRefusedBeforeAllocating) {
    // Two active voxels 1000 apart: a sparse file of a few kB whose dense box is 1001³ floats (3.7 GiB).
    auto sparse = openvdb::FloatGrid::create(0.0f);
    sparse->setName("density");
    sparse->getAccessor().setValue(openvdb::Coord(0), 1.0f);
    sparse->getAccessor().setValue(openvdb::Coord(1000), 1.0f);
    const std::string big = tempPath("big.vdb");
    writeVdb(big, {sparse});
    const MemoryLimit limit(64ull << 20);
    const uint64_t before = memoryCharged();
    const std::string err = errorOf([&] { makeGrid(big, false); });
    EXPECT_TRUE(contains(err, "scene.xml:6: " + big + ": grid 'density' densified to 1001x1001x1001x1 floats needs 3.74 GiB, over the memory limit")) << err;
    EXPECT_EQ(memoryCharged(), before);  // refused before anything was charged
    // Beyond 2^40 values it is refused with or without a limit.
    sparse->getAccessor().setValue(openvdb::Coord(1 << 14), 1.0f);
    writeVdb(big, {sparse});
    EXPECT_TRUE(contains(errorOf([&] { makeGrid(big, false); }), "too many to densify (over 2^40 values)"));
}
