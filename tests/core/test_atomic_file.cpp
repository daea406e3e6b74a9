// Atomic file output (core/io/atomic_file.h): a failed write (full disk, unwritable folder, a
// writer that throws) leaves the previous file intact and no temporary file behind.
#include <gtest/gtest.h>
#include <sys/mount.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <thread>

#include "core/io/atomic_file.h"
#include "core/io/image.h"
#include "tests/support/error_of.h"

namespace fs = std::filesystem;
using namespace iris;
using iris::test::errorOf;

namespace {

fs::path freshDir(const std::string& name) {
    const fs::path d = fs::path(::testing::TempDir()) / ("iris_atomic_" + std::to_string(::getpid()) + "_" + name);
    fs::remove_all(d);
    fs::create_directories(d);
    return d;
}

std::string contents(const fs::path& p) {
    std::ifstream f(p, std::ios::binary);
    std::stringstream ss;
    ss << f.rdbuf();
    return ss.str();
}

/// Files in `dir` other than `keep` (temporaries left behind).
int strayFiles(const fs::path& dir, const fs::path& keep) {
    int n = 0;
    for (const auto& e : fs::directory_iterator(dir))
        if (e.path() != keep) ++n;
    return n;
}

/// Sets an environment variable for the scope.
struct ScopedEnv {
    std::string name;
    ScopedEnv(std::string n, const std::string& v) : name(std::move(n)) { ::setenv(name.c_str(), v.c_str(), 1); }
    ~ScopedEnv() { ::unsetenv(name.c_str()); }
};

/// A noisy (incompressible) image of about 4 * 3 * w * h bytes.
Image noiseImage(int w, int h) {
    Image img(w, h, 3);
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (float& v : img.pixels) v = u(rng);
    return img;
}

}  // namespace

TEST(AtomicFile, WritesAndReplacesWithoutTemporaries) {
    const fs::path dir = freshDir("replace"), file = dir / "out.bin";
    writeFileAtomically(file.string(), "first");
    writeFileAtomically(file.string(), "second, longer");
    EXPECT_EQ(contents(file), "second, longer");
    EXPECT_EQ(strayFiles(dir, file), 0);
    // Temporary names are unique per call, so two writers of one path never share one.
    EXPECT_NE(atomicTempPath(file.string()), atomicTempPath(file.string()));
}

TEST(AtomicFile, ConcurrentWritersNeverMixTheirFiles) {
    const fs::path dir = freshDir("concurrent"), file = dir / "out.bin";
    const std::string a(1 << 16, 'a'), b(1 << 17, 'b');
    auto writeMany = [&](const std::string& s) {
        for (int i = 0; i < 40; ++i) writeFileAtomically(file.string(), s);
    };
    std::thread t1(writeMany, a), t2(writeMany, b);
    t1.join();
    t2.join();
    const std::string got = contents(file);
    EXPECT_TRUE(got == a || got == b) << "a mixed file of " << got.size() << " bytes";
    EXPECT_EQ(strayFiles(dir, file), 0);
}

TEST(AtomicFile, InjectedDiskFullKeepsTheOldFile) {
    const fs::path dir = freshDir("full"), file = dir / "out.bin";
    writeFileAtomically(file.string(), "old contents");
    {
        const ScopedEnv full("IRIS_FAULT_DISK_FULL_AFTER", "8");
        const std::string err = errorOf([&] { writeFileAtomically(file.string(), std::string(100, 'x')); });
        EXPECT_NE(err.find(file.string()), std::string::npos) << err;
        EXPECT_NE(err.find("No space left on device"), std::string::npos) << err;
        // The same for a file a library writes at the temporary path (EXR through OpenEXR).
        const fs::path exr = dir / "img.exr";
        const std::string exrErr = errorOf([&] { writeEXR(exr.string(), noiseImage(8, 8)); });
        EXPECT_NE(exrErr.find("No space left on device"), std::string::npos) << exrErr;
        EXPECT_FALSE(fs::exists(exr));
    }
    EXPECT_EQ(contents(file), "old contents");
    EXPECT_EQ(strayFiles(dir, file), 0);
    // Small enough writes still succeed under the injected limit (the hook is not "always fail").
    const ScopedEnv roomy("IRIS_FAULT_DISK_FULL_AFTER", "1000");
    writeFileAtomically(file.string(), "new");
    EXPECT_EQ(contents(file), "new");
}

TEST(AtomicFile, UnwritableFolderIsAClearError) {
    const fs::path dir = freshDir("unwritable");
    writeFileAtomically((dir / "plain").string(), "x");
    // A folder that is a regular file cannot hold anything (also as root, unlike chmod).
    const std::string target = (dir / "plain" / "out.exr").string();
    const std::string err = errorOf([&] { writeEXR(target, noiseImage(2, 2)); });
    EXPECT_NE(err.find(target), std::string::npos) << err;
    EXPECT_NE(err.find("Not a directory"), std::string::npos) << err;
    EXPECT_EQ(contents(dir / "plain"), "x");
}

TEST(AtomicFile, ThrowingWriterLeavesNoTemporary) {
    const fs::path dir = freshDir("throw"), file = dir / "out.bin";
    writeFileAtomically(file.string(), "kept");
    EXPECT_THROW(writeFileAtomicallyWith(file.string(),
                                         [](const std::string& tmp) {
                                             std::ofstream(tmp) << "partial";
                                             throw Error("writer failed");
                                         }),
                 Error);
    EXPECT_EQ(contents(file), "kept");
    EXPECT_EQ(strayFiles(dir, file), 0);
}

// A real full disk: a 64 KiB tmpfs mounted by the test (needs root; skipped otherwise).
TEST(AtomicFile, FullTmpfsKeepsThePreviousImage) {
    const fs::path dir = freshDir("tmpfs");
    if (::geteuid() != 0 || ::mount("tmpfs", dir.c_str(), "tmpfs", 0, "size=64k") != 0)
        GTEST_SKIP() << "cannot mount a tmpfs here (needs root)";
    struct Unmount {
        fs::path d;
        ~Unmount() { ::umount(d.c_str()); }
    } unmount{dir};
    const fs::path exr = dir / "out.exr";
    writeEXR(exr.string(), noiseImage(4, 4));
    const std::string before = contents(exr);
    // ~200 KB of incompressible pixels cannot fit in 64 KiB.
    const std::string err = errorOf([&] { writeEXR(exr.string(), noiseImage(128, 128)); });
    EXPECT_NE(err.find(exr.string()), std::string::npos) << err;
    EXPECT_EQ(contents(exr), before);
    EXPECT_EQ(readImage(exr.string()).width, 4);
    EXPECT_EQ(strayFiles(dir, exr), 0);
}
