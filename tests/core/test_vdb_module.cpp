// The OpenVDB module (libiris_vdb.so, loaded on demand, core/io/vdb_loader.h): the `render`
// executable no longer links OpenVDB (ldd lists no libopenvdb), reads a .vdb grid through the
// module, never needs it for a scene without one, and a missing or foreign module
// ($IRIS_VDB_MODULE) gives one clear error line naming the .vdb file, not a crash. Non-finite
// voxel values are refused by the module with the voxel named.
#include <gtest/gtest.h>

#include <openvdb/openvdb.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include "core/io/vdb_loader.h"
#include "core/io/vdb_reader.h"
#include "tests/support/app_runner.h"
#include "tests/support/error_of.h"
#include "tests/support/mapped_libraries.h"

using namespace iris;
using namespace iris::test;
using namespace iris::testing;

namespace {

std::string tempPath(const std::string& name) { return iris::testing::tempPath("iris_vdb_module", name); }

/// A .vdb holding one float grid "density" of 3x2x2 active voxels starting at (1, 2, 3), the
/// voxel at (2, 3, 4) set to `odd`.
std::string writeDensityVdb(const std::string& name, float odd = 0.75f) {
    openvdb::initialize();
    auto grid = openvdb::FloatGrid::create(0.0f);
    grid->setName("density");
    auto acc = grid->getAccessor();
    for (int k = 3; k < 5; ++k)
        for (int j = 2; j < 4; ++j)
            for (int i = 1; i < 4; ++i) acc.setValue(openvdb::Coord(i, j, k), 0.5f);
    acc.setValue(openvdb::Coord(2, 3, 4), odd);
    const std::string path = tempPath(name);
    openvdb::io::File(path).write({grid});
    return path;
}

/// A heterogeneous medium in a cube whose density is the grid of `vdb`.
std::string mediumScene(const std::string& vdb) {
    return R"(<scene version="3.0.0">
    <integrator type="volpath"/>
    <sensor type="perspective">
        <transform name="to_world"><lookat origin="0, 0, -4" target="0, 0, 0" up="0, 1, 0"/></transform>
        <sampler type="independent"><integer name="sample_count" value="2"/></sampler>
        <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/></film>
    </sensor>
    <medium type="heterogeneous" id="m"><volume type="gridvolume" name="sigma_t">
        <string name="filename" value=")" +
           vdb + R"("/><transform name="to_world"><translate value="-0.5, -0.5, -0.5"/></transform></volume></medium>
    <shape type="cube"><bsdf type="null"/><ref name="interior" id="m"/>
        <transform name="to_world"><scale value="0.5"/></transform></shape>
    <emitter type="constant"/>
</scene>
)";
}

/// A scene without any .vdb file.
std::string plainScene() {
    return R"(<scene version="3.0.0">
    <sensor type="perspective"><film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/></film>
        <sampler type="independent"><integer name="sample_count" value="1"/></sampler></sensor>
    <shape type="sphere"><bsdf type="diffuse"/></shape>
    <emitter type="constant"/>
</scene>
)";
}

/// `render scene -o out` with IRIS_VDB_MODULE=module ("": unset).
RunResult renderWithModule(const std::string& module, const std::string& scene, const std::string& out) {
    const std::string env = module.empty() ? "env -u IRIS_VDB_MODULE " : std::string(kVdbModuleEnv) + "=" + shellQuote(module) + " ";
    return runCommand(env + appPath("render") + " " + scene + " -o " + out + " --quiet --no-png --threads 1");
}

}  // namespace

TEST(VdbModule, RenderDoesNotLinkOpenVdb) {
    // ldd lists every library the loader maps at start-up, direct or not: OpenVDB (and the module)
    // must not be among them, or every process pays its relocation again.
    const RunResult r = runCommand("ldd " + appPath("render"));
    ASSERT_EQ(r.exitCode, 0) << r.stderrText;
    EXPECT_TRUE(contains(r.stdoutText, "libc.so")) << r.stdoutText;  // ldd did list the libraries
    EXPECT_FALSE(contains(r.stdoutText, "libopenvdb")) << r.stdoutText;
    EXPECT_FALSE(contains(r.stdoutText, "libiris_vdb")) << r.stdoutText;
}

TEST(VdbModule, LoadsTheModuleBesideTheBinary) {
    const std::string vdb = writeDensityVdb("beside.vdb");
    const VolumeGridData g = readVdbFile(vdb, "");
    EXPECT_EQ(g.xres, 3);
    EXPECT_EQ(g.yres, 2);
    EXPECT_EQ(g.zres, 2);
    EXPECT_EQ(g.at(1, 1, 1, 0), 0.75f);
    // The module that served this is the one beside the test binary (or $IRIS_VDB_MODULE).
    EXPECT_EQ(vdbModule(vdb, "test").path, vdbModulePath());
    EXPECT_TRUE(std::filesystem::exists(vdbModulePath())) << vdbModulePath();
    std::filesystem::remove(vdb);
}

TEST(VdbModule, NonFiniteValuesAreRefusedNamingTheVoxel) {
    const std::string inf = writeDensityVdb("inf.vdb", std::numeric_limits<float>::infinity());
    EXPECT_EQ(errorOf([&] { readVdbFile(inf, "density"); }), inf + ": grid 'density' has a non-finite value (inf) at voxel (2, 3, 4)");
    std::filesystem::remove(inf);
}

TEST(VdbModule, RenderReadsAVdbThroughTheModule) {
    const std::string vdb = writeDensityVdb("render.vdb");
    const std::string scene = tempPath("medium.xml"), out = tempPath("medium.exr");
    writeTextFile(scene, mediumScene(vdb));
    const RunResult r = renderWithModule("", scene, out);
    EXPECT_EQ(r.exitCode, 0) << r.stderrText;
    EXPECT_TRUE(std::filesystem::exists(out));
    for (const std::string& p : {vdb, scene, out}) std::filesystem::remove(p);
}

TEST(VdbModule, MissingOrForeignModuleGivesAClearErrorNamingTheFile) {
    const std::string vdb = writeDensityVdb("needs_module.vdb");
    const std::string scene = tempPath("needs_module.xml"), plain = tempPath("plain.xml"), out = tempPath("out.exr");
    writeTextFile(scene, mediumScene(vdb));
    writeTextFile(plain, plainScene());
    // A scene without a .vdb never needs the module.
    const std::string missing = "/nonexistent/libiris_vdb.so";
    RunResult r = renderWithModule(missing, plain, out);
    EXPECT_EQ(r.exitCode, 0) << r.stderrText;
    // One with a .vdb: one error line naming the .vdb file and the module.
    r = renderWithModule(missing, scene, out);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_TRUE(contains(r.stderrText, vdb + ": cannot read the OpenVDB file: the OpenVDB module " + missing)) << r.stderrText;
    EXPECT_TRUE(contains(r.stderrText, kVdbModuleEnv)) << r.stderrText;
    EXPECT_EQ(lineCount(r.stderrText), 1) << r.stderrText;
    // A file that is not a shared library, and a library that is not the module.
    const std::string notLib = tempPath("not_a_library.so");
    writeTextFile(notLib, "not an ELF file\n");
    r = renderWithModule(notLib, scene, out);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_TRUE(contains(r.stderrText, vdb + ": cannot read the OpenVDB file: the OpenVDB module " + notLib)) << r.stderrText;
    EXPECT_EQ(lineCount(r.stderrText), 1) << r.stderrText;
    const std::string zlib = mappedLibrary("/libz.so");
    ASSERT_FALSE(zlib.empty());
    r = renderWithModule(zlib, scene, out);
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_TRUE(contains(r.stderrText, "not an iris OpenVDB module (missing iris_vdb_abi_version")) << r.stderrText;
    EXPECT_TRUE(contains(r.stderrText, vdb)) << r.stderrText;
    EXPECT_EQ(lineCount(r.stderrText), 1) << r.stderrText;
    for (const std::string& p : {vdb, scene, plain, out, notLib}) std::filesystem::remove(p);
}
