// The `render` executable: renders a scene file to EXR + PNG with metadata, writes a valid partial
// image on SIGINT, and reports bad input as one line naming the file, with a non-zero exit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <fstream>

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


// Interruptions are raised by the renderer's test hook (IRIS_TEST_SIGNAL_AFTER_PASSES / _TILES,
// apps/render.cpp) at an exact point, so these tests do not depend on timing. kSmallScene is
// 32x24 pixels: 4 tiles of 16x16 per pass.
TEST(RenderApp, SigintWritesValidPartialImage) {
    const std::string scene = tempPath("long.xml"), out = tempPath("partial.exr");
    writeTextFile(scene, kSmallScene);
    const RunResult r = runCommand("IRIS_TEST_SIGNAL_AFTER_PASSES=3 " + appPath("render") + " " + scene + " -o " + out +
                                   " --spp 100000000 --quiet --no-png --threads 2");
    EXPECT_EQ(r.exitCode, 130) << r.stderrText;  // interrupted, image written
    const Image img = readImage(out);
    ASSERT_EQ(img.width, 32);
    const ImageMetadata meta = readEXRMetadata(out);
    EXPECT_EQ(metadataValue(meta, "iris.interrupted"), "1");
    EXPECT_EQ(metadataValue(meta, "iris.spp"), "3");  // exactly the passes finished before the signal
    EXPECT_EQ(metadataValue(meta, "iris.spp_max"), "3");
    for (float v : img.pixels) EXPECT_TRUE(std::isfinite(v));
}

TEST(RenderApp, SigtermMidPassKeepsEveryFinishedTile) {
    const std::string scene = tempPath("term.xml"), out = tempPath("term.exr");
    writeTextFile(scene, kSmallScene);
    // Tile 6 of the run is the second tile of pass 2 (one thread renders tiles in order).
    const RunResult r = runCommand("IRIS_TEST_SIGNAL=TERM IRIS_TEST_SIGNAL_AFTER_TILES=6 " + appPath("render") + " " + scene +
                                   " -o " + out + " --spp 50 --quiet --no-png --threads 1");
    EXPECT_EQ(r.exitCode, 130) << r.stderrText;
    const ImageMetadata meta = readEXRMetadata(out);
    EXPECT_EQ(metadataValue(meta, "iris.interrupted"), "1");
    EXPECT_EQ(metadataValue(meta, "iris.spp"), "1");
    EXPECT_EQ(metadataValue(meta, "iris.spp_max"), "2");
    for (float v : readImage(out).pixels) EXPECT_TRUE(std::isfinite(v));
    // The hook itself is checked: a bad value is refused rather than ignored.
    const RunResult bad = runCommand("IRIS_TEST_SIGNAL_AFTER_TILES=x " + appPath("render") + " " + scene + " -o " + out + " --quiet");
    EXPECT_EQ(bad.exitCode, 1);
    EXPECT_NE(bad.stderrText.find("IRIS_TEST_SIGNAL_AFTER_TILES"), std::string::npos) << bad.stderrText;
}

namespace {

/// The setting of the resume tests: a small scene rendered uninterrupted (`ref`), and the same
/// render interrupted in the middle of pass 3 with a checkpoint that keeps the two finished passes.
struct InterruptedRender {
    std::string scene, ref, out, ckpt, common;
    explicit InterruptedRender(const std::string& name)
        : scene(tempPath(name + ".xml")), ref(tempPath(name + "_ref.exr")), out(tempPath(name + "_out.exr")), ckpt(tempPath(name + ".ckpt")) {
        writeTextFile(scene, kSmallScene);
        common = " " + scene + " --spp 4 --seed 5 --quiet --no-png --threads 2";
        EXPECT_EQ(runCommand(appPath("render") + common + " -o " + ref).exitCode, 0);
        std::filesystem::remove(ckpt);
        const RunResult cut = run("IRIS_TEST_SIGNAL_AFTER_TILES=10", false);
        EXPECT_EQ(cut.exitCode, 130) << cut.stderrText;
    }
    /// `render` with the environment assignments `env`, writing `out` and keeping `ckpt`.
    RunResult run(const std::string& env, bool resume) const {
        return runCommand(env + " " + appPath("render") + common + " -o " + out + " --checkpoint " + ckpt + (resume ? " --resume" : ""));
    }
};

}  // namespace

TEST(RenderApp, InterruptedRenderResumesToTheUninterruptedImage) {
    const InterruptedRender r("resume");
    ASSERT_FALSE(::testing::Test::HasFailure());
    const std::string &out = r.out, &ckpt = r.ckpt;
    const RunResult resumed = r.run("", true);
    ASSERT_EQ(resumed.exitCode, 0) << resumed.stderrText;
    EXPECT_EQ(readImage(out).pixels, readImage(r.ref).pixels);

    // A corrupted checkpoint is refused (exit 1, one clear line), never resumed from.
    {
        std::fstream f(ckpt, std::ios::in | std::ios::out | std::ios::binary);
        f.seekp(200);
        f.put('\x7f');
    }
    std::filesystem::remove(out);
    const RunResult bad = r.run("", true);
    EXPECT_EQ(bad.exitCode, 1);
    EXPECT_NE(bad.stderrText.find(ckpt + ": checkpoint is corrupted"), std::string::npos) << bad.stderrText;
    EXPECT_FALSE(std::filesystem::exists(out));
    // ... and so is a truncated one.
    std::filesystem::resize_file(ckpt, 100);
    const RunResult cutFile = r.run("", true);
    EXPECT_EQ(cutFile.exitCode, 1);
    EXPECT_NE(cutFile.stderrText.find("truncated"), std::string::npos) << cutFile.stderrText;
}

// kill -9 in the middle of a checkpoint write (core/io/atomic_file.h's IRIS_FAULT_KILL_WRITING hook,
// no timing): the previous checkpoint stays byte-identical and resumes to the uninterrupted image.
TEST(RenderApp, SigkillDuringCheckpointWriteKeepsThePreviousCheckpoint) {
    const InterruptedRender r("kill");
    ASSERT_FALSE(::testing::Test::HasFailure());
    const std::string& ckpt = r.ckpt;
    const std::string before = fileBytes(ckpt);
    ASSERT_GT(before.size(), 1000u);

    // The resumed render finishes and is killed 1000 bytes into writing its final checkpoint.
    const RunResult killed = r.run("IRIS_FAULT_KILL_WRITING=1000", true);
    EXPECT_NE(killed.exitCode, 0);
    EXPECT_NE(killed.exitCode, 1) << killed.stderrText;  // killed, not an error exit
    EXPECT_EQ(fileBytes(ckpt), before);
    // The killed write really was half done: its temporary holds exactly the 1000 bytes.
    int temporaries = 0;
    for (const auto& e : std::filesystem::directory_iterator(std::filesystem::path(ckpt).parent_path()))
        if (e.path().string().rfind(ckpt + ".tmp-", 0) == 0) {
            ++temporaries;
            EXPECT_EQ(std::filesystem::file_size(e.path()), 1000u);
            std::filesystem::remove(e.path());
        }
    EXPECT_EQ(temporaries, 1);

    const RunResult resumed = r.run("", true);
    ASSERT_EQ(resumed.exitCode, 0) << resumed.stderrText;
    EXPECT_EQ(readImage(r.out).pixels, readImage(r.ref).pixels);
}

TEST(RenderApp, FailedOutputWriteKeepsThePreviousImage) {
    const std::string scene = tempPath("full.xml"), out = tempPath("full.exr");
    writeTextFile(scene, kSmallScene);
    const std::string args = " " + scene + " -o " + out + " --spp 1 --quiet --no-png";
    ASSERT_EQ(runCommand(appPath("render") + args + " --seed 1").exitCode, 0);
    const std::vector<float> before = readImage(out).pixels;
    // A disk with 100 bytes free (core/io/atomic_file.h's fault hook).
    const RunResult r = runCommand("IRIS_FAULT_DISK_FULL_AFTER=100 " + appPath("render") + args + " --seed 2");
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.stderrText.find(out + ": write failed: No space left on device"), std::string::npos) << r.stderrText;
    EXPECT_EQ(readImage(out).pixels, before);
    for (const auto& e : std::filesystem::directory_iterator(std::filesystem::path(out).parent_path()))
        EXPECT_EQ(e.path().string().find(out + ".tmp"), std::string::npos) << e.path();
    // An output folder that cannot exist: a usage error, found before the scene is loaded (issue 38).
    const RunResult r2 = runCommand(appPath("render") + " " + scene + " -o " + scene + "/x.exr --spp 1 --quiet --no-png");
    EXPECT_EQ(r2.exitCode, 2);
    EXPECT_NE(r2.stderrText.find(scene + "/x.exr: " + scene + " is not a folder"), std::string::npos) << r2.stderrText;
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

TEST(RenderApp, MomentIntegratorWritesFirstAndSecondMomentChannels) {
    std::string xml = kSmallScene;
    const std::string path = R"(<integrator type="path"/>)";
    xml.replace(xml.find(path), path.size(), R"(<integrator type="moment"><integrator type="path"/></integrator>)");
    const std::string scene = tempPath("moment.xml"), out = tempPath("moment.exr");
    writeTextFile(scene, xml);
    const RunResult r = runCommand(appPath("render") + " " + scene + " -o " + out + " --spp 4 --mode rgb --no-png --quiet");
    ASSERT_EQ(r.exitCode, 0) << r.stderrText;
    const Image img = readImage(out);
    ASSERT_EQ(img.channels, 9);
    const int m1 = img.channelIndex("moment1.G"), m2 = img.channelIndex("moment2.G"), g = img.channelIndex("G");
    ASSERT_GE(m1, 0);
    ASSERT_GE(m2, 0);
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            EXPECT_FLOAT_EQ(img.at(x, y, m1), img.at(x, y, g));  // RGB mode: the film is linear Rec.709
            EXPECT_GE(img.at(x, y, m2) * (1 + 1e-5f), img.at(x, y, m1) * img.at(x, y, m1));  // E[X²] >= E[X]²
        }
    EXPECT_EQ(metadataValue(readEXRMetadata(out), "iris.integrator"), "moment");
}

TEST(RenderApp, SamplerOptionChoosesTheSequenceAndSppNamesThePattern) {
    const std::string scene = tempPath("sampler.xml"), out = tempPath("sampler.exr"), ckpt = tempPath("sampler.ckpt");
    writeTextFile(scene, kSmallScene);
    const std::string app = appPath("render") + " " + scene + " -o " + out + " --quiet --no-png";
    ASSERT_EQ(runCommand(app + " --spp 2 --sampler sobol").exitCode, 0);
    EXPECT_EQ(metadataValue(readEXRMetadata(out), "iris.sampler"), "sobol");
    ASSERT_EQ(runCommand(app + " --spp 2 --sampler highdimsobol").exitCode, 0);
    EXPECT_EQ(metadataValue(readEXRMetadata(out), "iris.sampler"), "highdimsobol");
    // --spp names the pattern of the whole render even after --spp-range, whose count it keeps.
    std::filesystem::remove(ckpt);
    const RunResult shard = runCommand(app + " --spp-range 0:2 --spp 4 --sampler stratified --checkpoint " + ckpt);
    ASSERT_EQ(shard.exitCode, 0) << shard.stderrText;
    const ImageMetadata meta = readEXRMetadata(out);
    EXPECT_EQ(metadataValue(meta, "iris.sampler"), "stratified/4");
    EXPECT_EQ(metadataValue(meta, "iris.spp_target"), "2");
    const RunResult bad = runCommand(app + " --sampler halton");
    EXPECT_EQ(bad.exitCode, 2);
    EXPECT_NE(bad.stderrText.find("unknown sampler 'halton' (supported: independent, stratified, multijitter, sobol, highdimsobol)"), std::string::npos)
        << bad.stderrText;
}

// A signal at start-up (before the handlers: the default action ends the process) or when the
// output's temporary is complete but not yet renamed leaves the previous image byte for byte, or
// no image; never a partial one (hooks IRIS_TEST_SIGNAL_AT_START, IRIS_FAULT_SIGNAL_BEFORE_RENAME).
TEST(RenderApp, SignalAtStartUpOrBeforeTheRenameLeavesThePreviousImageOrNone) {
    const std::string scene = tempPath("sigmoment.xml"), out = tempPath("sigmoment.exr");
    writeTextFile(scene, kSmallScene);
    const std::string app = appPath("render") + " " + scene + " -o " + out + " --spp 1 --quiet --no-png";
    auto removeTemporaries = [&] {
        int n = 0;
        for (const auto& e : std::filesystem::directory_iterator(std::filesystem::path(out).parent_path()))
            if (e.path().string().rfind(out + ".tmp-", 0) == 0) {
                std::filesystem::remove(e.path());
                ++n;
            }
        return n;
    };
    for (const std::string hook : {"IRIS_TEST_SIGNAL_AT_START=1 IRIS_TEST_SIGNAL=TERM", "IRIS_TEST_SIGNAL_AT_START=1",
                                   "IRIS_FAULT_SIGNAL_BEFORE_RENAME=INT", "IRIS_FAULT_SIGNAL_BEFORE_RENAME=TERM"}) {
        ASSERT_EQ(runCommand(app + " --seed 1").exitCode, 0);
        const std::string before = fileBytes(out);
        const RunResult r = runCommand(hook + " " + app + " --seed 2");
        EXPECT_NE(r.exitCode, 0) << hook;
        EXPECT_NE(r.exitCode, 1) << hook << ": " << r.stderrText;  // ended by the signal, not an error
        EXPECT_EQ(fileBytes(out), before) << hook;
        const bool atRename = hook.find("RENAME") != std::string::npos;
        EXPECT_EQ(removeTemporaries(), atRename ? 1 : 0) << hook;  // the complete, unrenamed temporary
        std::filesystem::remove(out);
        EXPECT_NE(runCommand(hook + " " + app + " --seed 2").exitCode, 0) << hook;
        EXPECT_FALSE(std::filesystem::exists(out)) << hook;
        removeTemporaries();
    }
}
