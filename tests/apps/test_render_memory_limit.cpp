// render --memory-limit and IRIS_MEMORY_LIMIT (issue 19 item 4): a scene over the limit stops
// before rendering with a one-line message and exit code 1; a bad size is a usage error (2); a
// limit the scene fits renders as before.
#include <gtest/gtest.h>

#include <filesystem>

#include "core/source_tree.h"
#include "tests/support/app_runner.h"

using iris::testing::runCommand;

namespace {

std::string renderCommand(const std::string& options, const std::string& env = "") {
    const std::string out = iris::testing::tempPath("memory_limit", "out.exr");
    return env + " " + iris::testing::appPath("render") + " " + iris::sourcePath("scenes/default.xml") + " -o " + out +
           " --quiet --no-png --spp 1 " + options;
}

}  // namespace

TEST(RenderMemoryLimit, ASceneOverTheLimitStopsWithItsSize) {
    const auto r = runCommand(renderCommand("--memory-limit 1M"));
    EXPECT_EQ(r.exitCode, 1) << r.stderrText;
    EXPECT_NE(r.stderrText.find("default.xml:"), std::string::npos) << r.stderrText;
    EXPECT_NE(r.stderrText.find("film of 256x256 pixels needs 7 MiB, over the memory limit of 1 MiB"), std::string::npos)
        << r.stderrText;
}

TEST(RenderMemoryLimit, TheEnvironmentVariableSetsTheLimitToo) {
    const auto r = runCommand(renderCommand("", "IRIS_MEMORY_LIMIT=2M"));
    EXPECT_EQ(r.exitCode, 1) << r.stderrText;
    EXPECT_NE(r.stderrText.find("over the memory limit of 2 MiB"), std::string::npos) << r.stderrText;
    const auto bad = runCommand(renderCommand("", "IRIS_MEMORY_LIMIT=lots"));
    EXPECT_EQ(bad.exitCode, 1) << bad.stderrText;
    EXPECT_NE(bad.stderrText.find("IRIS_MEMORY_LIMIT: invalid memory size 'lots'"), std::string::npos) << bad.stderrText;
}

TEST(RenderMemoryLimit, ABadSizeIsAUsageErrorAndAFittingLimitRenders) {
    const auto bad = runCommand(renderCommand("--memory-limit 4X"));
    EXPECT_EQ(bad.exitCode, 2) << bad.stderrText;
    EXPECT_NE(bad.stderrText.find("--memory-limit: invalid memory size '4X'"), std::string::npos) << bad.stderrText;
    const auto ok = runCommand(renderCommand("--memory-limit 64M"));
    EXPECT_EQ(ok.exitCode, 0) << ok.stderrText;
}
