// Image I/O: EXR values and metadata survive a round trip, writes are atomic (no temp file left),
// LDR output is clamped and rounded, and bad files are reported as iris::Error naming the path.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "core/error.h"
#include "core/image.h"
#include "core/rng.h"

using namespace iris;
namespace fs = std::filesystem;

namespace {

/// A fresh directory per test, removed afterwards.
class ImageIO : public ::testing::Test {
protected:
    void SetUp() override {
        dir = fs::temp_directory_path() /
              strCat("iris_test_image_", ::getpid(), "_", ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(dir);
        fs::create_directories(dir);
    }
    void TearDown() override { fs::remove_all(dir); }
    std::string file(const std::string& name) const { return (dir / name).string(); }
    fs::path dir;
};

Image randomImage(int w, int h, int c, uint64_t seed) {
    Image img(w, h, c);
    Pcg32 rng(seed, 1);
    for (float& v : img.pixels) v = (rng.uniform() - 0.25f) * 100.0f;  // negative and large values too
    return img;
}

/// Expect `fn` to throw an iris::Error whose message contains `path`.
template <typename Fn>
void expectErrorNaming(Fn fn, const std::string& path) {
    try {
        fn();
        ADD_FAILURE() << "no error for " << path;
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    }
}

}  // namespace

TEST_F(ImageIO, ExrRoundTripIsExactWithMetadata) {
    Image img = randomImage(17, 9, 3, 42);
    img.at(3, 4, 1) = 1e30f;
    img.at(0, 0, 2) = -0.0f;
    const ImageMetadata meta = {{"iris.spp", "64"}, {"iris.seed", "7"}, {"iris.scene", "scenes/a b.xml"}};
    const std::string p = file("round.exr");
    writeEXR(p, img, meta);
    const Image back = readImage(p);
    ASSERT_EQ(back.width, 17);
    ASSERT_EQ(back.height, 9);
    ASSERT_EQ(back.channels, 3);
    EXPECT_EQ(back.channelNames, (std::vector<std::string>{"R", "G", "B"}));
    for (size_t i = 0; i < img.pixels.size(); ++i) ASSERT_EQ(back.pixels[i], img.pixels[i]) << "value " << i;
    const ImageMetadata m = readEXRMetadata(p);
    for (const auto& [k, v] : meta) EXPECT_EQ(metadataValue(m, k), v) << k;
    EXPECT_EQ(metadataValue(m, "absent", "def"), "def");
}

TEST_F(ImageIO, ExtraChannelsKeepTheirNames) {
    Image img = randomImage(4, 3, 5, 1);
    img.channelNames = {"R", "G", "B", "depth", "var"};
    const std::string p = file("aov.exr");
    writeEXR(p, img);
    const Image back = readImage(p);
    ASSERT_EQ(back.channels, 5);
    for (const std::string& name : img.channelNames) {
        const int cb = back.channelIndex(name), ci = img.channelIndex(name);
        ASSERT_GE(cb, 0) << name;
        for (int y = 0; y < 3; ++y)
            for (int x = 0; x < 4; ++x) EXPECT_EQ(back.at(x, y, cb), img.at(x, y, ci)) << name;
    }
}

TEST_F(ImageIO, AtomicWriteLeavesNoTempFileAndReplacesOld) {
    const std::string p = file("a.exr");
    writeEXR(p, randomImage(5, 5, 3, 1));
    writeEXR(p, randomImage(6, 2, 3, 2));  // overwrite
    writeLDR(file("a.png"), Image(3, 3, 3));
    int count = 0;
    for (const auto& entry : fs::directory_iterator(dir)) {
        ++count;
        EXPECT_EQ(entry.path().string().find(".tmp-"), std::string::npos) << entry.path();
    }
    EXPECT_EQ(count, 2);
    EXPECT_EQ(readImage(p).width, 6);
}

TEST_F(ImageIO, FailedWriteLeavesNothingAndNamesTheFile) {
    const std::string p = file("missing_dir/x.exr");
    expectErrorNaming([&] { writeEXR(p, Image(2, 2, 3)); }, p);
    expectErrorNaming([&] { writeEXR(file("empty.exr"), Image()); }, file("empty.exr"));
    EXPECT_TRUE(fs::is_empty(dir));
}

TEST_F(ImageIO, LdrIsClampedAndRounded) {
    Image img(4, 1, 3);
    const float values[4] = {-1.0f, 0.5f, 2.0f, 0.2f};
    for (int x = 0; x < 4; ++x)
        for (int c = 0; c < 3; ++c) img.at(x, 0, c) = values[x];
    const std::string p = file("ldr.png");
    writeLDR(p, img);
    const Image back = readImage(p);  // OIIO returns 8-bit values as code/255
    ASSERT_EQ(back.width, 4);
    const float expected[4] = {0.0f, 128.0f / 255.0f, 1.0f, 51.0f / 255.0f};
    for (int x = 0; x < 4; ++x) EXPECT_NEAR(back.at(x, 0, 0), expected[x], 1e-6f) << x;
}

TEST_F(ImageIO, MissingFileThrowsNamingPath) {
    const std::string p = file("does_not_exist.exr");
    expectErrorNaming([&] { readImage(p); }, p);
    expectErrorNaming([&] { readEXRMetadata(p); }, p);
}

TEST_F(ImageIO, TruncatedExrThrowsNamingPath) {
    const std::string p = file("trunc.exr");
    writeEXR(p, randomImage(64, 64, 3, 5));
    const auto size = fs::file_size(p);
    fs::resize_file(p, size / 2);
    expectErrorNaming([&] { readImage(p); }, p);
    fs::resize_file(p, 20);  // header cut too
    expectErrorNaming([&] { readImage(p); }, p);
    expectErrorNaming([&] { readEXRMetadata(p); }, p);
}

TEST_F(ImageIO, TextFileNamedExrThrowsNamingPath) {
    const std::string p = file("text.exr");
    std::ofstream(p) << "this is not an image\n";
    expectErrorNaming([&] { readImage(p); }, p);
    expectErrorNaming([&] { readEXRMetadata(p); }, p);
}

namespace {

/// Bytes of an uncompressed scanline EXR header claiming w x h FLOAT "Y" pixels, with a valid-looking
/// offset table but no pixel data (OpenEXR file layout, openexr.com).
std::string hugeExrHeader(int w, int h) {
    std::string s;
    auto i32 = [&](int32_t v) { s.append(reinterpret_cast<const char*>(&v), 4); };
    auto attr = [&](const std::string& name, const std::string& type, const std::string& value) {
        s += name + '\0' + type + '\0';
        i32(int32_t(value.size()));
        s += value;
    };
    auto ints = [](std::initializer_list<int32_t> v) {
        std::string out;
        for (int32_t x : v) out.append(reinterpret_cast<const char*>(&x), 4);
        return out;
    };
    i32(20000630);
    i32(2);
    attr("channels", "chlist", std::string("Y\0", 2) + ints({2}) + std::string(4, '\0') + ints({1, 1}) + std::string(1, '\0'));
    attr("compression", "compression", std::string(1, '\0'));
    attr("dataWindow", "box2i", ints({0, 0, w - 1, h - 1}));
    attr("displayWindow", "box2i", ints({0, 0, w - 1, h - 1}));
    attr("lineOrder", "lineOrder", std::string(1, '\0'));
    attr("pixelAspectRatio", "float", ints({0x3f800000}));
    attr("screenWindowCenter", "v2f", ints({0, 0}));
    attr("screenWindowWidth", "float", ints({0x3f800000}));
    s += '\0';
    const uint64_t end = s.size() + 8ull * uint64_t(h);
    for (int y = 0; y < h; ++y) s.append(reinterpret_cast<const char*>(&end), 8);
    return s;
}

}  // namespace

TEST_F(ImageIO, AbsurdSizeIsRefusedBeforeAllocating) {
    const std::string p = file("huge.exr");
    std::ofstream(p, std::ios::binary) << hugeExrHeader(20000, 20000);  // 4e8 > 2^28 pixels
    try {
        readImage(p);
        ADD_FAILURE() << "no error";
    } catch (const Error& e) {
        const std::string msg = e.what();
        EXPECT_NE(msg.find(p), std::string::npos) << msg;
        EXPECT_NE(msg.find("2^28"), std::string::npos) << msg;
    }
}

TEST_F(ImageIO, JpegDropsAlpha) {
    Image img(4, 2, 4);
    for (float& v : img.pixels) v = 0.5f;
    const std::string p = file("x.jpg");
    writeLDR(p, img);
    const Image back = readImage(p);
    EXPECT_EQ(back.channels, 3);
    EXPECT_NEAR(back.at(1, 1, 0), 128.0f / 255.0f, 3.0f / 255.0f);  // lossy
}
