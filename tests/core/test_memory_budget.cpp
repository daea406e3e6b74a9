// The memory budget (core/memory_budget.h, issue 19 item 4): sizes parsed as users write them,
// charges held by an account and given back, and the readers and the loader refusing what would
// not fit before they allocate it, with a message naming the file and what was too large.
#include <gtest/gtest.h>

#include <cstring>
#include <functional>
#include <fstream>

#include "core/error.h"
#include "core/io/image.h"
#include "core/io/obj_reader.h"
#include "core/io/ply_reader.h"
#include "core/memory_budget.h"
#include "render/loader/scene_loader.h"
#include "tests/support/app_runner.h"

using namespace iris;

namespace {

/// Sets a limit for one test and restores the one before (the default, in a fresh process) after it.
struct ScopedLimit {
    explicit ScopedLimit(uint64_t bytes) : before(memoryLimit()) { setMemoryLimit(bytes); }
    ~ScopedLimit() { setMemoryLimit(before); }
    uint64_t before;
};

std::string errorOf(const std::function<void()>& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

std::string writeTemp(const std::string& name, const std::string& bytes) {
    const std::string path = iris::testing::tempPath("memory_budget", name);
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
}

/// A binary PLY of n vertices (all at the origin, 1-byte coordinates: 3 bytes in the file, 12 in
/// the mesh) and one triangle.
std::string plyWithVertices(int n) {
    std::string s = "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(n) +
                    "\nproperty char x\nproperty char y\nproperty char z\nelement face 1\n"
                    "property list uchar int vertex_indices\nend_header\n";
    s.append(size_t(n) * 3, '\0');
    s += '\3';
    for (int i : {0, 1, 2}) s.append(reinterpret_cast<const char*>(&i), 4);
    return s;
}

}  // namespace

TEST(MemoryBudget, ParsesSizesWithBinaryUnits) {
    EXPECT_EQ(parseByteSize("0"), 0u);
    EXPECT_EQ(parseByteSize("1000000"), 1000000u);
    EXPECT_EQ(parseByteSize("512M"), 512ull << 20);
    EXPECT_EQ(parseByteSize("4G"), 4ull << 30);
    EXPECT_EQ(parseByteSize("4g"), 4ull << 30);
    EXPECT_EQ(parseByteSize("1.5GiB"), 3ull << 29);
    EXPECT_EQ(parseByteSize("800KB"), 800ull << 10);
    EXPECT_EQ(parseByteSize("2T"), 2ull << 40);
    EXPECT_EQ(parseByteSize("64B"), 64u);
    for (const char* bad : {"", "M", "-1G", "4X", "4 G", "1e9", "4GG", "nan", "99999999999T"})
        EXPECT_NE(errorOf([&] { parseByteSize(bad); }).find("invalid memory size"), std::string::npos) << bad;
    EXPECT_EQ(formatBytes(512), "512 B");
    EXPECT_EQ(formatBytes(1536), "1.5 KiB");
    EXPECT_EQ(formatBytes(3ull << 30), "3 GiB");
}

TEST(MemoryBudget, AnAccountHoldsItsChargesUntilItsReservationGoes) {
    const ScopedLimit limit(1000);
    const uint64_t before = memoryCharged();
    std::shared_ptr<const MemoryReservation> held;
    {
        MemoryAccount account;
        chargeMemory(600, "first");
        EXPECT_EQ(memoryCharged(), before + 600);
        const std::string e = errorOf([] { chargeMemory(500, "x.ply: 41 vertices"); });
        EXPECT_NE(e.find("x.ply: 41 vertices needs 500 B, over the memory limit of 1000 B (600 B already in use"), std::string::npos) << e;
        EXPECT_EQ(memoryCharged(), before + 600);  // the refused charge holds nothing
        held = account.take();
    }
    EXPECT_EQ(held->bytes(), 600u);
    EXPECT_EQ(memoryCharged(), before + 600);
    held.reset();
    EXPECT_EQ(memoryCharged(), before);
    {
        MemoryAccount failedLoad;
        chargeMemory(900, "not taken");
    }
    EXPECT_EQ(memoryCharged(), before);  // an account not taken gives its charges back
    chargeMemory(900, "outside any account");  // checked only
    EXPECT_EQ(memoryCharged(), before);
    EXPECT_FALSE(errorOf([] { chargeMemory(1001, "alone too large"); }).empty());
}

TEST(MemoryBudget, PlyVerticesAreRefusedFromTheHeaderCounts) {
    const std::string path = writeTemp("big.ply", plyWithVertices(4000));  // 12 kB file, 47 KiB of vertices
    EXPECT_EQ(readPly(path).positions.size(), 4000u);                  // no limit: reads
    const ScopedLimit limit(32 << 10);
    MemoryAccount account;  // as the loader holds one
    const std::string e = errorOf([&] { readPly(path); });
    EXPECT_NE(e.find(path + ": 4000 vertices (PLY header) needs 46.9 KiB, over the memory limit of 32 KiB"), std::string::npos) << e;
    const ScopedLimit tight(1000);
    EXPECT_NE(errorOf([&] { readPly(path); }).find(path + ": reading the PLY file needs"), std::string::npos);
}

TEST(MemoryBudget, ObjAndImagesAreCharged) {
    const std::string obj = writeTemp("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    Image img(64, 64, 3);
    const std::string exr = iris::testing::tempPath("memory_budget", "img.exr");
    writeEXR(exr, img);
    const ScopedLimit limit(40000);  // the EXR file fits, its 48 KiB of floats do not
    EXPECT_NE(errorOf([&] { readImage(exr); }).find(exr + ": image of 64x64x3 floats needs 48 KiB, over the memory limit"),
              std::string::npos);
    const ScopedLimit tiny(40);  // the 32-byte OBJ file fits, its mesh (36 + 12 bytes) does not
    MemoryAccount account;
    EXPECT_NE(errorOf([&] { readObj(obj); }).find(obj + ": 3 vertices and 1 triangles needs 48 B"), std::string::npos);
}

TEST(MemoryBudget, TheLoaderRefusesAFilmAndGivesBackWhatAFailedLoadCharged) {
    const std::string xml = R"(<scene version="3.0.0">
<sensor type="perspective">
  <film type="hdrfilm"><integer name="width" value="2000"/><integer name="height" value="1000"/></film>
</sensor>
</scene>)";
    const uint64_t before = memoryCharged();
    {
        const SceneDescription scene = loadSceneFromString(xml, ".");
        ASSERT_TRUE(scene.memory);
        EXPECT_EQ(scene.memory->bytes(), 2000ull * 1000 * (76 + 36));
        EXPECT_EQ(memoryCharged(), before + scene.memory->bytes());
    }
    EXPECT_EQ(memoryCharged(), before);  // given back with the scene
    const ScopedLimit limit(100 << 20);
    const std::string e = errorOf([&] { loadSceneFromString(xml, "."); });
    EXPECT_NE(e.find("<string>:2: film of 2000x1000 pixels needs 214 MiB, over the memory limit of 100 MiB"), std::string::npos) << e;
    EXPECT_EQ(memoryCharged(), before);
}
