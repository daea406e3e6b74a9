// Checkpoints that must not be resumed from: truncated, corrupted (CRC-32), an older format or
// another file are refused with a clear error, and the film is left as it was.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "render/film.h"
#include "tests/support/error_of.h"

namespace fs = std::filesystem;
using namespace iris;
using iris::test::errorOf;

namespace {

std::string tempFile(const std::string& name) {
    return (fs::path(::testing::TempDir()) / ("iris_ckpt_" + std::to_string(::getpid()) + "_" + name)).string();
}

std::string readAll(const std::string& p) {
    std::ifstream f(p, std::ios::binary);
    std::stringstream ss;
    ss << f.rdbuf();
    return ss.str();
}

void writeAll(const std::string& p, const std::string& s) { std::ofstream(p, std::ios::binary) << s; }

Film filmWithSamples() {
    Film film(5, 4);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 5; ++x) film.addSample(x, y, vec3(float(x), float(y), 1.0f));
    return film;
}

/// Load `bytes` as a checkpoint into a fresh film; returns the error (or "").
std::string loadError(const std::string& bytes, const std::string& name) {
    const std::string p = tempFile(name);
    writeAll(p, bytes);
    Film film(5, 4);
    const std::string err = errorOf([&] { film.load(p, "key"); });
    if (!err.empty()) EXPECT_EQ(film.totalSamples(), 0u) << "a refused checkpoint changed the film";
    return err;
}

}  // namespace

TEST(CheckpointFaults, RoundTripIsExact) {
    const std::string p = tempFile("good.ckpt");
    const Film a = filmWithSamples();
    a.save(p, "key");
    Film b(5, 4);
    b.load(p, "key");
    EXPECT_EQ(b.meanImage(), a.meanImage());
    EXPECT_EQ(b.totalSamples(), a.totalSamples());
}

TEST(CheckpointFaults, TruncatedCorruptedAndForeignFilesAreRefused) {
    const std::string p = tempFile("src.ckpt");
    filmWithSamples().save(p, "key");
    const std::string good = readAll(p);
    ASSERT_TRUE(loadError(good, "ok.ckpt").empty());

    for (size_t keep : {size_t(0), size_t(5), size_t(20), good.size() / 2, good.size() - 1}) {
        const std::string err = loadError(good.substr(0, keep), "trunc.ckpt");
        EXPECT_TRUE(err.find("truncated") != std::string::npos || err.find("not an iris checkpoint") != std::string::npos)
            << keep << ": " << err;
    }
    for (size_t at : {size_t(30), good.size() / 2, good.size() - 5}) {
        std::string bad = good;
        bad[at] = char(bad[at] ^ 0x10);
        const std::string err = loadError(bad, "flip.ckpt");
        EXPECT_NE(err.find("corrupted"), std::string::npos) << at << ": " << err;
        EXPECT_NE(err.find("flip.ckpt"), std::string::npos) << err;
    }
    std::string older = good;
    older[7] = '2';
    EXPECT_NE(loadError(older, "v2.ckpt").find("format version 2"), std::string::npos);
    EXPECT_NE(loadError("just some text, long enough to be read", "text.ckpt").find("not an iris checkpoint"), std::string::npos);
    EXPECT_NE(loadError(good + "extra", "long.ckpt").find("wrong size"), std::string::npos);
}

TEST(CheckpointFaults, OtherSettingsAreRefused) {
    const std::string p = tempFile("other.ckpt");
    filmWithSamples().save(p, "key");
    Film film(5, 4);
    EXPECT_NE(errorOf([&] { film.load(p, "other key"); }).find("different scene or settings"), std::string::npos);
    Film bigger(6, 4);
    EXPECT_FALSE(errorOf([&] { bigger.load(p, "key"); }).empty());
    EXPECT_EQ(bigger.totalSamples(), 0u);
}
