// One render split into sample ranges by hand (what a Slurm array does, without Slurm): `render
// --spp-range A:B --checkpoint` shards merged by `merge` give the unsplit render's EXR pixels bit
// for bit; a shard of another seed or scene file is refused with a message naming it.
#include <gtest/gtest.h>

#include <filesystem>

#include "core/io/image.h"
#include "core/source_tree.h"
#include "tests/support/app_runner.h"

using namespace iris;
using namespace iris::testing;

namespace {
std::string tmp(const std::string& name) { return iris::testing::tempPath("iris_split", name); }

std::string scene() { return sourcePath("scenes/default.xml"); }

RunResult renderShard(const std::string& range, const std::string& name, const std::string& extra = "") {
    return runCommand(appPath("render") + " " + scene() + " -D res=48 --seed 3 --quiet --no-png --spp-range " + range +
                      " --checkpoint " + tmp(name + ".state") + " -o " + tmp(name + ".exr") + " " + extra);
}
}  // namespace

TEST(SplitRender, ShardsMergeToTheUnsplitImageBitForBit) {
    const RunResult full = runCommand(appPath("render") + " " + scene() + " -D res=48 --seed 3 --quiet --no-png --spp 10 -o " +
                                      tmp("full.exr"));
    ASSERT_EQ(full.exitCode, 0) << full.stderrText;
    for (const auto& [range, name] : {std::pair{"0:4", "s0"}, {"4:7", "s1"}, {"7:10", "s2"}})
        ASSERT_EQ(renderShard(range, name).exitCode, 0) << range;
    const std::string shards = tmp("s2.state") + " " + tmp("s0.state") + " " + tmp("s1.state");
    const RunResult m = runCommand(appPath("merge") + " --quiet --spp 10 -o " + tmp("merged.exr") + " " + shards);
    ASSERT_EQ(m.exitCode, 0) << m.stderrText;
    const Image a = readImage(tmp("full.exr")), b = readImage(tmp("merged.exr"));
    ASSERT_EQ(a.width, b.width);
    EXPECT_EQ(a.pixels, b.pixels);
    EXPECT_EQ(metadataValue(readEXRMetadata(tmp("merged.exr")), "iris.spp"), "10");
    // One shard's EXR alone differs (the comparison can fail).
    EXPECT_NE(readImage(tmp("s0.exr")).pixels, a.pixels);

    // A missing last shard is found with --spp; a shard of another seed is refused by name.
    const RunResult gap = runCommand(appPath("merge") + " --spp 10 -o " + tmp("bad.exr") + " " + tmp("s0.state") + " " + tmp("s1.state"));
    EXPECT_EQ(gap.exitCode, 1);
    EXPECT_NE(gap.stderrText.find("samples 7:10 are missing"), std::string::npos) << gap.stderrText;
    ASSERT_EQ(renderShard("7:10", "seed4", "--seed 4").exitCode, 0);
    const RunResult seed = runCommand(appPath("merge") + " -o " + tmp("bad.exr") + " " + tmp("s0.state") + " " + tmp("s1.state") + " " +
                                      tmp("seed4.state"));
    EXPECT_EQ(seed.exitCode, 1);
    EXPECT_NE(seed.stderrText.find(tmp("seed4.state") + ": different scene or settings"), std::string::npos) << seed.stderrText;
    // Another -D override is another scene (its hash differs).
    ASSERT_EQ(renderShard("7:10", "other", "-D spp=3").exitCode, 0);
    const RunResult other = runCommand(appPath("merge") + " -o " + tmp("bad.exr") + " " + tmp("s0.state") + " " + tmp("s1.state") + " " +
                                       tmp("other.state"));
    EXPECT_EQ(other.exitCode, 1);
    EXPECT_FALSE(std::filesystem::exists(tmp("bad.exr")));
    for (const char* n : {"full.exr", "merged.exr", "s0", "s1", "s2", "seed4", "other"}) {
        std::filesystem::remove(tmp(n));
        std::filesystem::remove(tmp(std::string(n) + ".exr"));
        std::filesystem::remove(tmp(std::string(n) + ".state"));
    }
}

TEST(SplitRender, SppRangeNeedsACheckpointAndAValidRange) {
    const RunResult noState = runCommand(appPath("render") + " " + scene() + " --spp-range 0:4 -o " + tmp("x.exr"));
    EXPECT_EQ(noState.exitCode, 2);
    EXPECT_NE(noState.stderrText.find("--spp-range needs --checkpoint"), std::string::npos) << noState.stderrText;
    const RunResult empty = runCommand(appPath("render") + " " + scene() + " --spp-range 4:4 --checkpoint " + tmp("x.state"));
    EXPECT_EQ(empty.exitCode, 2);
    EXPECT_NE(empty.stderrText.find("0 <= A < B"), std::string::npos) << empty.stderrText;
}
