// The `render` executable: renders a scene file to EXR + PNG with metadata, writes a valid partial
// image on SIGINT, and reports bad input as one line naming the file, with a non-zero exit.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <thread>

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include "tests/support/app_runner.h"
#include "core/io/image.h"

using namespace iris;
using namespace iris::testing;

namespace {

const char* kSmallScene = R"(<scene version="3.0.0">
    <default name="spp" value="4"/>
    <integrator type="path"/>
    <sensor type="perspective">
        <float name="fov" value="40"/>
        <transform name="to_world"><lookat origin="0, 0, -4" target="0, 0, 0" up="0, 1, 0"/></transform>
        <sampler type="independent"><integer name="sample_count" value="$spp"/></sampler>
        <film type="hdrfilm"><integer name="width" value="32"/><integer name="height" value="24"/></film>
    </sensor>
    <shape type="sphere"><bsdf type="diffuse"/></shape>
    <emitter type="constant"><float name="radiance" value="1"/></emitter>
</scene>
)";

std::string tempPath(const std::string& name) { return iris::testing::tempPath("iris_app", name); }

}  // namespace

TEST(RenderApp, RendersSceneWithMetadata) {
    const std::string scene = tempPath("small.xml"), out = tempPath("small.exr");
    writeTextFile(scene, kSmallScene);
    const RunResult r = runCommand(appPath("render") + " " + scene + " -o " + out + " --spp 3 --seed 9 --spectral-samples 8 --quiet");
    ASSERT_EQ(r.exitCode, 0) << r.stderrText;
    const Image img = readImage(out);
    EXPECT_EQ(img.width, 32);
    EXPECT_EQ(img.height, 24);
    EXPECT_TRUE(std::filesystem::exists(std::filesystem::path(out).replace_extension(".png")));
    const ImageMetadata meta = readEXRMetadata(out);
    EXPECT_EQ(metadataValue(meta, "iris.mode"), "spectral");
    EXPECT_EQ(metadataValue(meta, "iris.spectral_samples"), "8");
    EXPECT_EQ(metadataValue(meta, "iris.spp"), "3");
    EXPECT_EQ(metadataValue(meta, "iris.seed"), "9");
    EXPECT_FALSE(metadataValue(meta, "iris.version").empty());
    EXPECT_GT(std::stoll(metadataValue(meta, "iris.rays", "0")), 32 * 24 * 3);
    EXPECT_FALSE(metadataValue(meta, "iris.render_time_s").empty());

    // RGB mode and -D overrides.
    const RunResult r2 = runCommand(appPath("render") + " " + scene + " -o " + out + " -D spp=2 --mode rgb --quiet --no-png");
    ASSERT_EQ(r2.exitCode, 0) << r2.stderrText;
    const ImageMetadata meta2 = readEXRMetadata(out);
    EXPECT_EQ(metadataValue(meta2, "iris.mode"), "rgb");
    EXPECT_EQ(metadataValue(meta2, "iris.spp"), "2");
    EXPECT_EQ(metadataValue(meta2, "iris.rgb_wavelengths"), "645,525,445");
}

TEST(RenderApp, VarianceFileHoldsXyzVarianceOfTheMean) {
    const std::string scene = tempPath("var.xml"), out = tempPath("var.exr"), var = tempPath("var_var.exr");
    writeTextFile(scene, kSmallScene);
    for (const char* mode : {"spectral", "rgb"}) {
        const RunResult r = runCommand(appPath("render") + " " + scene + " -o " + out + " --variance " + var +
                                       " --spp 4 --mode " + mode + " --quiet --no-png");
        ASSERT_EQ(r.exitCode, 0) << r.stderrText;
        const Image v = readImage(var);
        ASSERT_EQ(v.channels, 3);
        std::vector<std::string> names = v.channelNames;  // OpenImageIO may list Y (luminance) first
        std::sort(names.begin(), names.end());
        EXPECT_EQ(names, (std::vector<std::string>{"X", "Y", "Z"}));
        double sum = 0.0;
        for (float x : v.pixels) {
            EXPECT_GE(x, 0.0f);
            sum += x;
        }
        EXPECT_GT(sum, 0.0) << mode;  // a lit scene at 4 spp has noise
        EXPECT_EQ(metadataValue(readEXRMetadata(var), "iris.spp"), "4");
    }
    // The RGB film's XYZ moments are not part of a checkpoint: the combination is refused.
    const RunResult bad = runCommand(appPath("render") + " " + scene + " -o " + out + " --variance " + var +
                                     " --checkpoint " + tempPath("c.ckpt") + " --mode rgb --quiet");
    EXPECT_EQ(bad.exitCode, 2);
}

TEST(RenderApp, SigintWritesValidPartialImage) {
    const std::string scene = tempPath("long.xml"), out = tempPath("partial.exr");
    writeTextFile(scene, kSmallScene);
    const std::string app = appPath("render");
    std::vector<std::string> args = {app, scene, "-o", out, "--spp", "100000000", "--quiet", "--no-png", "--threads", "1"};
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    pid_t pid;
    ASSERT_EQ(posix_spawn(&pid, app.c_str(), nullptr, nullptr, argv.data(), environ), 0);
    // Wait until the render is under way (a few passes of this tiny image take milliseconds).
    std::this_thread::sleep_for(std::chrono::milliseconds(1500));
    ASSERT_EQ(kill(pid, SIGINT), 0);
    int status = 0;
    ASSERT_EQ(waitpid(pid, &status, 0), pid);
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 130);  // interrupted, image written
    const Image img = readImage(out);
    ASSERT_EQ(img.width, 32);
    const ImageMetadata meta = readEXRMetadata(out);
    EXPECT_EQ(metadataValue(meta, "iris.interrupted"), "1");
    const long long spp = std::stoll(metadataValue(meta, "iris.spp", "0"));
    EXPECT_GT(spp, 0);
    EXPECT_LT(spp, 100000000);
    for (float v : img.pixels) EXPECT_TRUE(std::isfinite(v));
}

TEST(RenderApp, BadInputGivesOneLineErrorAndNonZeroExit) {
    const std::string app = appPath("render");
    // Missing scene file.
    RunResult r = runCommand(app + " /nonexistent/scene.xml -o " + tempPath("x.exr") + " --quiet");
    EXPECT_NE(r.exitCode, 0);
    EXPECT_NE(r.stderrText.find("/nonexistent/scene.xml"), std::string::npos) << r.stderrText;

    // Missing mesh file referenced by a scene.
    const std::string scene = tempPath("missing_mesh.xml");
    writeTextFile(scene, R"(<scene version="3.0.0">
    <shape type="obj"><string name="filename" value="no_such_mesh.obj"/></shape>
</scene>
)");
    r = runCommand(app + " " + scene + " -o " + tempPath("x.exr") + " --quiet");
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.stderrText.find("no_such_mesh.obj"), std::string::npos) << r.stderrText;
    EXPECT_EQ(std::count(r.stderrText.begin(), r.stderrText.end(), '\n'), 1) << r.stderrText;

    // Unreadable environment map.
    const std::string bad = tempPath("not_an_image.exr");
    writeTextFile(bad, "this is not an EXR file");
    const std::string envScene = tempPath("bad_env.xml");
    writeTextFile(envScene, "<scene version=\"3.0.0\">\n<emitter type=\"envmap\"><string name=\"filename\" value=\"" + bad +
                                "\"/></emitter>\n</scene>\n");
    r = runCommand(app + " " + envScene + " -o " + tempPath("x.exr") + " --quiet");
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.stderrText.find("not_an_image.exr"), std::string::npos) << r.stderrText;
    EXPECT_NE(r.stderrText.find("bad_env.xml:2"), std::string::npos) << r.stderrText;

    // A -D override the scene does not know would silently change nothing: it is an error.
    const std::string small = tempPath("small_for_define.xml");
    writeTextFile(small, kSmallScene);
    r = runCommand(app + " " + small + " -o " + tempPath("x.exr") + " --quiet -D thickness=80");
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.stderrText.find("no parameter 'thickness'"), std::string::npos) << r.stderrText;

    // Invalid option values.
    for (const std::string opt : {"--spp abc", "--spectral-samples 0", "--spectral-samples 33", "--mode cmyk", "--threads -1",
                                  "--rgb-wavelengths 1,2", "--bogus"}) {
        r = runCommand(app + " " + opt);
        EXPECT_EQ(r.exitCode, 2) << opt;
        EXPECT_NE(r.stderrText.find("render:"), std::string::npos) << opt;
    }
}
