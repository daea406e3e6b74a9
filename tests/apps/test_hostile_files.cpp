// Issue 38, through the `render` executable: no input hangs or eats the machine, and no render is
// lost to a bad output path. Every hostile file is made by the test. Each command runs under
// runCommand's timeout (a hang fails with exit code 124) and, outside AddressSanitizer (whose shadow
// memory needs terabytes of address space), under `ulimit -v 4000000`: a reader that grew a buffer
// from /dev/zero or allocated the 3 GiB image would end in std::bad_alloc, not the message asserted.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <regex>

#include "core/io/image.h"
#include "core/source_tree.h"
#include "tests/support/app_runner.h"
#include "tests/support/hostile_files.h"

using namespace iris;
using namespace iris::testing;
namespace fs = std::filesystem;

namespace {

#if defined(__SANITIZE_ADDRESS__)
const std::string kAddressLimit;
#else
const std::string kAddressLimit = "ulimit -v 4000000; ";  // 3.81 GiB of address space
#endif
constexpr int kHangSeconds = 60;  // far beyond the second these take; a hang is killed and fails

std::string path(const std::string& name) { return tempPath("hostile_files", name); }

/// A 16×16 scene of one sphere whose body lines (from line 2) are `body`.
std::string sceneWith(const std::string& name, const std::string& body) {
    const std::string file = path(name);
    writeTextFile(file, "<scene version=\"3.0.0\">\n" + body +
                            "<sensor type=\"perspective\"><film type=\"hdrfilm\"><integer name=\"width\" value=\"16\"/>"
                            "<integer name=\"height\" value=\"16\"/></film></sensor>\n</scene>\n");
    return file;
}

RunResult render(const std::string& scene, const std::string& options, const std::string& env = "") {
    return runCommand(kAddressLimit + env + " " + appPath("render") + " " + scene + " --quiet --no-png " + options, kHangSeconds);
}

void expectRefusal(const RunResult& r, int exitCode, const std::string& message) {
    EXPECT_EQ(r.exitCode, exitCode) << r.stderrText;
    EXPECT_NE(r.stderrText.find(message), std::string::npos) << "expected: " << message << "\ngot: " << r.stderrText;
}

}  // namespace

// Items 1 and 3: a device or FIFO named as an image, a spectrum or an include. Before the fix the
// envmap never returned and the .spd and include grew a buffer to gigabytes.
TEST(HostileFiles, ADeviceOrFifoAsImageSpectrumOrIncludeIsRefusedAtOnce) {
    const std::string fifo = makeFifo(path("fifo.exr"));
    const struct {
        std::string body, message;
    } cases[] = {
        {"<emitter type=\"envmap\"><string name=\"filename\" value=\"/dev/zero\"/></emitter>\n",
         ":2: /dev/zero: cannot open image: it is a character device, not a regular file"},
        {"<emitter type=\"envmap\"><string name=\"filename\" value=\"" + fifo + "\"/></emitter>\n",
         ":2: " + fifo + ": cannot open image: it is a FIFO (named pipe), not a regular file"},
        {"<shape type=\"sphere\"><bsdf type=\"diffuse\"><texture type=\"bitmap\" name=\"reflectance\">"
         "<string name=\"filename\" value=\"/dev/zero\"/></texture></bsdf></shape>\n",
         "/dev/zero: cannot open image: it is a character device"},
        {"<shape type=\"sphere\"><bsdf type=\"diffuse\"><spectrum name=\"reflectance\" filename=\"/dev/zero\"/></bsdf></shape>\n",
         ":2: /dev/zero: cannot open spectrum file: it is a character device, not a regular file"},
        {"<shape type=\"sphere\"><bsdf type=\"diffuse\"><spectrum name=\"reflectance\" filename=\"/dev/urandom\"/></bsdf></shape>\n",
         ":2: /dev/urandom: cannot open spectrum file: it is a character device"},
        {"<include filename=\"/dev/zero\"/>\n", ":2: /dev/zero: cannot open included file: it is a character device"},
    };
    int n = 0;
    for (const auto& c : cases) {
        const std::string out = path("device.exr");
        const RunResult r = render(sceneWith("device" + std::to_string(n++) + ".xml", c.body), "--spp 1 -o " + out);
        expectRefusal(r, 1, c.message);
        EXPECT_FALSE(fs::exists(out));
    }
}

// Item 2: a valid 97 KB DWAB EXR of 16384^2 pixels (3 GiB as floats) as an environment map is
// refused from its header; the same kind of file at 2048^2 (within the allowance for small images)
// renders, so the check does not refuse DWAB files as such.
TEST(HostileFiles, ASmallFileClaimingAHugeImageIsRefusedFromItsHeader) {
    const std::string huge = path("huge_dwab.exr"), small = path("small_dwab.exr");
    writeConstantDwabExr(huge, 16384);
    ASSERT_EQ(fs::file_size(huge), 97529u);  // the file
    writeConstantDwabExr(small, 2048);
    const std::string out = path("dwab.exr");
    const auto envmap = [](const std::string& file) {
        return "<emitter type=\"envmap\"><string name=\"filename\" value=\"" + file + "\"/></emitter>\n";
    };
    expectRefusal(render(sceneWith("huge_dwab.xml", envmap(huge)), "--spp 1 -o " + out),
                  1, huge + ": header claims 16384x16384x3 samples (3 GiB as floats), more than a 97529-byte file can hold");
    EXPECT_FALSE(fs::exists(out));
    const RunResult ok = render(sceneWith("small_dwab.xml", envmap(small)), "--spp 1 -o " + out);
    EXPECT_EQ(ok.exitCode, 0) << ok.stderrText;
    EXPECT_NEAR(readImage(out).at(0, 0, 1), 0.5f, 0.05f);  // the constant environment, seen beside the sphere
}

// Item 4: output paths and usage are checked before the scene loads. The scene here does not exist,
// so a check made after loading would report the scene (the last case shows that it would).
TEST(HostileFiles, BadOutputPathsAndUsageAreRefusedBeforeTheSceneLoads) {
    const std::string missingScene = path("no_such_scene.xml"), folder = path("a_folder");
    fs::create_directories(folder);
    expectRefusal(render(missingScene, "-o /nonexistent/dir/out.exr --time-limit 600"), 2,
                  "-o /nonexistent/dir/out.exr: the folder /nonexistent/dir does not exist");
    expectRefusal(render(missingScene, "-o " + folder + " --time-limit 600"), 2, "-o " + folder + ": is a directory");
    expectRefusal(render(missingScene, "-o /dev/null --spp 1"), 2, "-o /dev/null: exists and is not a regular file");
    expectRefusal(render(missingScene, "-o " + path("ok.exr") + " --spectral-output " + folder), 2, "--spectral-output " + folder);
    expectRefusal(render(missingScene, "-o " + path("ok.exr") + " --checkpoint /nonexistent/c.ckpt"), 2,
                  "--checkpoint /nonexistent/c.ckpt: the folder /nonexistent does not exist");
    expectRefusal(render(missingScene, "-o " + path("ok.exr") + " --spp 0"), 2, "--spp 0 needs --time-limit");
    expectRefusal(render(missingScene, "-o " + path("ok.exr") + " --spp 1 --output-space no_such_space"), 2,
                  "--output-space: colour space 'no_such_space' is not in");
    expectRefusal(render(missingScene, "-o " + path("ok.exr") + " --spp 1"), 1, "no_such_scene.xml: cannot open scene file: file not found");
}

// Item 4: when the final write fails after all (here injected: IRIS_FAULT_UNWRITABLE), the image goes
// to a fallback path in the current folder that the error names, and the exit code says it failed.
TEST(HostileFiles, AFailedFinalWriteIsRescuedToAPathTheErrorNames) {
    const std::string work = path("rescue");
    fs::remove_all(work);
    fs::create_directories(work + "/out");
    const std::string out = work + "/out/image.exr";
    const std::string cmd = appPath("render") + " " + sourcePath("scenes/default.xml") + " -D res=24 --spp 1 --quiet --no-png -o " + out;
    const RunResult r = runCommand("cd " + work + " && IRIS_FAULT_UNWRITABLE=" + out + " " + cmd, kHangSeconds);
    EXPECT_EQ(r.exitCode, 1) << r.stderrText;
    std::smatch m;
    ASSERT_TRUE(std::regex_search(r.stderrText, m, std::regex(out + ": cannot create file: Read-only file system; written to (\\S+) instead")))
        << r.stderrText;
    const std::string rescued = m[1];
    EXPECT_EQ(fs::path(rescued).parent_path(), fs::path(work));
    EXPECT_EQ(readImage(rescued).width, 24);
    EXPECT_FALSE(fs::exists(out));
    const RunResult ok = runCommand("cd " + work + " && " + cmd, kHangSeconds);  // without the fault: the image where asked, nothing rescued
    EXPECT_EQ(ok.exitCode, 0) << ok.stderrText;
    EXPECT_EQ(readImage(out).width, 24);
    int rescuedFiles = 0;
    for (const auto& e : fs::directory_iterator(work)) rescuedFiles += e.path().filename().string().rfind("iris-rescued-", 0) == 0;
    EXPECT_EQ(rescuedFiles, 1);
}

// A checkpoint that cannot be written where asked loses nothing either: the render goes on, the
// image is written, and the final film state goes to a fallback path that the error names and from
// which the render resumes.
TEST(HostileFiles, AFailedCheckpointWriteIsRescuedAndTheImageStillWritten) {
    const std::string work = path("rescue_checkpoint");
    fs::remove_all(work);
    fs::create_directories(work + "/out");
    const std::string out = work + "/out/image.exr", ckpt = work + "/out/state.ckpt";
    const std::string cmd = appPath("render") + " " + sourcePath("scenes/default.xml") + " -D res=16 --quiet --no-png -o " + out +
                            " --checkpoint " + ckpt;
    const RunResult r = runCommand("cd " + work + " && IRIS_FAULT_UNWRITABLE=" + ckpt + " " + cmd + " --spp 2", kHangSeconds);
    EXPECT_EQ(r.exitCode, 1) << r.stderrText;
    EXPECT_EQ(readImage(out).width, 16);  // the image is where it was asked
    std::smatch m;
    ASSERT_TRUE(std::regex_search(r.stderrText, m, std::regex("--checkpoint " + ckpt + ": .*written to (\\S+) instead"))) << r.stderrText;
    const std::string rescued = m[1];
    EXPECT_FALSE(fs::exists(ckpt));
    // The rescued state is a real checkpoint: the render resumes from it to 4 samples.
    const RunResult resumed = runCommand("cd " + work + " && " + appPath("render") + " " + sourcePath("scenes/default.xml") +
                                             " -D res=16 --quiet --no-png -o " + out + " --checkpoint " + rescued + " --resume --spp 4",
                                         kHangSeconds);
    EXPECT_EQ(resumed.exitCode, 0) << resumed.stderrText;
}

// Item 5: --memory-limit bounds a scene of many spheres, from the size of its XML before it is
// parsed (10^5 spheres here, 13 MB of XML; 10^6 behave alike at ten times the size), and the same
// scene renders under a limit it fits.
TEST(HostileFiles, TheMemoryLimitBoundsASceneOfManySpheres) {
    std::string body = "<bsdf type=\"diffuse\" id=\"d\"/>\n";
    for (int i = 0; i < 100000; ++i)
        body += "<shape type=\"sphere\"><point name=\"center\" x=\"" + std::to_string(i % 317) + "\" y=\"" + std::to_string(i / 317) +
                "\" z=\"900\"/><float name=\"radius\" value=\"0.4\"/><ref id=\"d\"/></shape>\n";
    const std::string scene = sceneWith("spheres.xml", body), out = path("spheres.exr");
    const RunResult r = render(scene, "--spp 1 -o " + out + " --memory-limit 64M");
    expectRefusal(r, 1, scene + ": parsing 11.7 MiB of scene XML needs 187 MiB");
    expectRefusal(r, 1, "over the memory limit of 64 MiB");
    const RunResult ok = render(scene, "--spp 1 -o " + out + " --memory-limit 1G");
    EXPECT_EQ(ok.exitCode, 0) << ok.stderrText;
}

// The default budget (no option, no variable) is half of what the process may use: under
// `ulimit -v 4000000` 1.91 GiB, which a 5000x5000 film (2.6 GiB of sums and images) exceeds; it is
// refused before allocating, naming where the default came from.
TEST(HostileFiles, TheDefaultMemoryLimitIsHalfOfWhatTheProcessMayUse) {
#if defined(__SANITIZE_ADDRESS__)
    GTEST_SKIP() << "needs ulimit -v, which AddressSanitizer cannot run under";
#endif
    const std::string scene = path("big_film.xml");
    writeTextFile(scene, "<scene version=\"3.0.0\"><sensor type=\"perspective\"><film type=\"hdrfilm\">"
                         "<integer name=\"width\" value=\"5000\"/><integer name=\"height\" value=\"5000\"/></film></sensor></scene>\n");
    const std::string run = "ulimit -v 4000000; env -u IRIS_MEMORY_LIMIT " + appPath("render") + " " + scene + " --quiet --spp 1 -o " + path("big.exr");
    const RunResult r = runCommand(run, kHangSeconds);
    expectRefusal(r, 1, "film of 5000x5000 pixels needs 2.61 GiB, over the memory limit of 1.91 GiB");
    expectRefusal(r, 1, "the default limit is 50 % of the 3.81 GiB of ulimit -v");
}
