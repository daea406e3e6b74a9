// Image I/O: EXR values and metadata survive a round trip, writes are atomic (no temp file left),
// LDR output is clamped and rounded, and bad files are reported as iris::Error naming the path.
// EXR files read with OpenEXR equal what OpenImageIO (the general path, the module) reads.
#include <gtest/gtest.h>

#include <unistd.h>

#include <bit>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfMultiPartOutputFile.h>
#include <OpenEXR/ImfOutputPart.h>
#include <OpenEXR/ImfPartType.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfTiledOutputFile.h>

#include "core/error.h"
#include "core/io/image.h"
#include "core/io/oiio_loader.h"
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

/// Bytes of an EXR header claiming w x h FLOAT "Y" pixels with the given compression code (0: none,
/// 4: PIZ) and, when tileX > 0, tiles of tileX x tileY pixels, with a valid-looking offset table but
/// no pixel data (OpenEXR file layout, openexr.com).
/// compression -1: no "compression" attribute (OpenEXR then keeps its Header default, ZIP).
std::string hugeExrHeader(int w, int h, int compression = 0, int tileX = 0, int tileY = 0) {
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
    i32(tileX > 0 ? 2 | 0x200 : 2);  // version 2; flag 0x200: single-part tiled
    attr("channels", "chlist", std::string("Y\0", 2) + ints({2}) + std::string(4, '\0') + ints({1, 1}) + std::string(1, '\0'));
    if (compression >= 0) attr("compression", "compression", std::string(1, char(compression)));
    attr("dataWindow", "box2i", ints({0, 0, w - 1, h - 1}));
    attr("displayWindow", "box2i", ints({0, 0, w - 1, h - 1}));
    attr("lineOrder", "lineOrder", std::string(1, '\0'));
    attr("pixelAspectRatio", "float", ints({0x3f800000}));
    attr("screenWindowCenter", "v2f", ints({0, 0}));
    attr("screenWindowWidth", "float", ints({0x3f800000}));
    if (tileX > 0) attr("tiles", "tiledesc", ints({tileX, tileY}) + std::string(1, '\0'));
    s += '\0';
    const uint64_t end = s.size() + 8ull * uint64_t(h);
    for (int y = 0; y < h; ++y) s.append(reinterpret_cast<const char*>(&end), 8);
    return s;
}

/// Expect readImage(p) to fail with an iris::Error naming p and containing `what`.
void expectRefusal(const std::string& p, const std::string& what) {
    try {
        readImage(p);
        ADD_FAILURE() << "no error";
    } catch (const Error& e) {
        const std::string msg = e.what();
        EXPECT_NE(msg.find(p), std::string::npos) << msg;
        EXPECT_NE(msg.find(what), std::string::npos) << msg;
    }
}

}  // namespace

TEST_F(ImageIO, AbsurdSizeIsRefusedBeforeAllocating) {
    const std::string p = file("huge.exr");
    std::ofstream(p, std::ios::binary) << hugeExrHeader(20000, 20000);  // 4e8 > 2^28 pixels
    expectRefusal(p, "2^28");
}

// OpenEXR sizes its decompression buffer from the compression's block of scan lines, whatever the
// data window's height: a one-line window 2^25 pixels wide is a 4 GB PIZ block (32 lines) but a
// 128 MB uncompressed one. Found by fuzz_image (tests/fuzz/corpus/image/oom-exr-compressor-lines).
TEST_F(ImageIO, ExrCompressorBlockIsRefusedBeforeAllocating) {
    const std::string piz = file("piz.exr");
    std::ofstream(piz, std::ios::binary) << hugeExrHeader(1 << 25, 1, 4);
    expectRefusal(piz, "needs more than 1 GB per block of 32 scan lines");
    // The same window uncompressed passes the check and fails only for want of pixel data.
    const std::string none = file("none.exr");
    std::ofstream(none, std::ios::binary) << hugeExrHeader(1 << 25, 1, 0);
    expectRefusal(none, "cannot read");
    // Without a "compression" attribute OpenEXR keeps its default, ZIP (16 lines a block): a
    // one-line window 2^24 pixels wide is then a 2 GB block, not a 128 MB uncompressed one (found by
    // fuzz_image: tests/fuzz/corpus/image/oom-exr-default-compression allocated 1 GiB).
    const std::string unnamed = file("default_compression.exr");
    std::ofstream(unnamed, std::ios::binary) << hugeExrHeader(1 << 24, 1, -1);
    expectRefusal(unnamed, "needs more than 1 GB per block of 16 scan lines");
}

TEST_F(ImageIO, ExrTileClaimIsRefusedBeforeAllocating) {
    const std::string p = file("tiles.exr");
    std::ofstream(p, std::ios::binary) << hugeExrHeader(4, 4, 0, 1 << 16, 1 << 16);  // a 2^32-pixel tile
    expectRefusal(p, "need more than 1 GB per tile");
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

// ---- EXR through OpenEXR vs the general path (OpenImageIO module) --------------------------

namespace {

/// Write an EXR directly with OpenEXR: the given channel names and pixel type, a data window
/// offset from the origin, optionally tiled; values are a deterministic pattern (negative, large
/// and fractional values; exactly representable in HALF where the type is HALF).
void writeExrWith(const std::string& path, const std::vector<std::string>& names, Imf::PixelType type,
                  const Imath::Box2i& dw, bool tiled) {
    Imf::Header header(Imath::Box2i(Imath::V2i(0, 0), Imath::V2i(dw.max.x + 2, dw.max.y + 3)), dw);
    header.compression() = Imf::PIZ_COMPRESSION;
    const int w = dw.max.x - dw.min.x + 1, h = dw.max.y - dw.min.y + 1;
    const size_t n = size_t(w) * size_t(h);
    std::vector<std::vector<float>> f(names.size(), std::vector<float>(n));
    std::vector<std::vector<half>> hv(names.size(), std::vector<half>(n));
    std::vector<std::vector<uint32_t>> u(names.size(), std::vector<uint32_t>(n));
    Imf::FrameBuffer fb;
    for (size_t c = 0; c < names.size(); ++c) {
        header.channels().insert(names[c], Imf::Channel(type));
        for (size_t i = 0; i < n; ++i) {
            const float v = (float(int((i * 7 + c * 13) % 29)) - 9.0f) * 0.375f + float(c) * 100.0f;
            f[c][i] = v;
            hv[c][i] = half(v);
            u[c][i] = uint32_t(i * 1000003u + c);
        }
        char* base = type == Imf::FLOAT  ? reinterpret_cast<char*>(f[c].data())
                     : type == Imf::HALF ? reinterpret_cast<char*>(hv[c].data())
                                         : reinterpret_cast<char*>(u[c].data());
        const size_t xs = type == Imf::HALF ? sizeof(half) : 4;
        fb.insert(names[c], Imf::Slice(type, base - (dw.min.x + dw.min.y * w) * xs, xs, xs * size_t(w)));
    }
    if (tiled) {
        header.setTileDescription(Imf::TileDescription(4, 4, Imf::ONE_LEVEL));
        Imf::TiledOutputFile file(path.c_str(), header);
        file.setFrameBuffer(fb);
        file.writeTiles(0, file.numXTiles() - 1, 0, file.numYTiles() - 1);
    } else {
        Imf::OutputFile file(path.c_str(), header);
        file.setFrameBuffer(fb);
        file.writePixels(h);
    }
}

void expectSameImage(const Image& a, const Image& b, const std::string& what) {
    ASSERT_EQ(a.width, b.width) << what;
    ASSERT_EQ(a.height, b.height) << what;
    ASSERT_EQ(a.channels, b.channels) << what;
    EXPECT_EQ(a.channelNames, b.channelNames) << what;
    ASSERT_EQ(a.pixels.size(), b.pixels.size()) << what;
    for (size_t i = 0; i < a.pixels.size(); ++i)
        ASSERT_EQ(std::bit_cast<uint32_t>(a.pixels[i]), std::bit_cast<uint32_t>(b.pixels[i])) << what << " value " << i;
}

}  // namespace

TEST_F(ImageIO, ExrReadByOpenExrEqualsOpenImageIO) {
    // Channel sets exercising OpenImageIO's reordering (layers; R, G, B, A, Y, Z, ... first).
    const std::vector<std::vector<std::string>> channelSets = {
        {"R", "G", "B"},
        {"R", "G", "B", "A"},
        {"Y"},
        {"depth", "R", "var", "A", "B"},
        {"b.R", "a.G", "a.R", "R", "G", "B", "a.B", "Z", "A"},
        {"diffuse.B", "diffuse.G", "diffuse.R", "alpha", "x"},
        {"Y", "RY", "BY"},
        {"red", "green", "blue", "alpha"},
        {"A", "a", "Z", "ZBack", "DEPTH", "imag", "real", "AR", "RA"},
        {"x", "W", "a.x", "a.W", "a.b.R", "ab.R"},
    };
    int k = 0;
    for (const auto& names : channelSets)
        for (const Imf::PixelType type : {Imf::FLOAT, Imf::HALF})
            for (const bool tiled : {false, true}) {
                const std::string p = file(strCat("set", k++, ".exr"));
                writeExrWith(p, names, type, Imath::Box2i(Imath::V2i(3, -2), Imath::V2i(13, 6)), tiled);
                ImageFileInfo info;
                info.integerFormat = true;
                const Image direct = readImage(p, &info);
                EXPECT_FALSE(info.integerFormat);
                EXPECT_EQ(direct.width, 11);
                EXPECT_EQ(direct.height, 9);
                expectSameImage(direct, readImageWithOpenImageIO(p), p);
            }
    // What the renderer writes (FLOAT, ZIP, R G B + extra channels).
    Image img = randomImage(7, 5, 5, 3);
    img.channelNames = {"R", "G", "B", "depth", "var"};
    writeEXR(file("w.exr"), img);
    expectSameImage(readImage(file("w.exr")), readImageWithOpenImageIO(file("w.exr")), "writeEXR");
}

TEST_F(ImageIO, MultiPartExrReadsTheFirstPartLikeOpenImageIO) {
    // Two parts with different channels and sizes: both paths read part 0 only.
    std::vector<Imf::Header> headers;
    for (int part = 0; part < 2; ++part) {
        // Parts share the display window; their data windows differ.
        Imf::Header h(Imath::Box2i(Imath::V2i(0, 0), Imath::V2i(4, 3)),
                      Imath::Box2i(Imath::V2i(0, 0), Imath::V2i(3 + part, 2 + part)));
        h.setName(part == 0 ? "beauty" : "aov");
        h.setType(Imf::SCANLINEIMAGE);
        for (const char* c : part == 0 ? std::vector<const char*>{"B", "G", "R"} : std::vector<const char*>{"Z", "N.x"})
            h.channels().insert(c, Imf::Channel(Imf::FLOAT));
        headers.push_back(h);
    }
    const std::string p = file("multi.exr");
    {
        Imf::MultiPartOutputFile out(p.c_str(), headers.data(), int(headers.size()));
        for (int part = 0; part < 2; ++part) {
            const int w = 4 + part, h = 3 + part, n = part == 0 ? 3 : 2;
            std::vector<float> px(size_t(w * h * n));
            for (size_t i = 0; i < px.size(); ++i) px[i] = float(i) * 0.5f - float(part) * 7.0f;
            Imf::FrameBuffer fb;
            int c = 0;
            for (auto it = headers[size_t(part)].channels().begin(); it != headers[size_t(part)].channels().end(); ++it, ++c)
                fb.insert(it.name(), Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(px.data() + c), sizeof(float) * size_t(n),
                                                sizeof(float) * size_t(n * w)));
            Imf::OutputPart o(out, part);
            o.setFrameBuffer(fb);
            o.writePixels(h);
        }
    }
    const Image direct = readImage(p);
    EXPECT_EQ(direct.width, 4);
    EXPECT_EQ(direct.channels, 3);
    expectSameImage(direct, readImageWithOpenImageIO(p), p);
}

TEST_F(ImageIO, UintExrChannelsGoThroughOpenImageIO) {
    // OpenImageIO normalises UINT channels; such files keep being read by it, unchanged.
    const std::string p = file("uint.exr");
    writeExrWith(p, {"id", "R"}, Imf::UINT, Imath::Box2i(Imath::V2i(0, 0), Imath::V2i(4, 3)), false);
    expectSameImage(readImage(p), readImageWithOpenImageIO(p), p);
}

TEST_F(ImageIO, PngAndJpegGoThroughTheModule) {
    Image img(5, 3, 3);
    for (size_t i = 0; i < img.pixels.size(); ++i) img.pixels[i] = float(i % 11) / 10.0f;
    const std::string p = file("m.png");
    writeLDR(p, img);
    ImageFileInfo info;
    const Image back = readImage(p, &info);
    EXPECT_TRUE(info.integerFormat);
    ASSERT_EQ(back.channels, 3);
    EXPECT_EQ(back.channelNames, (std::vector<std::string>{"R", "G", "B"}));
    for (size_t i = 0; i < img.pixels.size(); ++i)
        EXPECT_NEAR(back.pixels[i], float(std::lround(img.pixels[i] * 255.0f)) / 255.0f, 1e-6f) << i;
    expectSameImage(back, readImageWithOpenImageIO(p), p);
    // The module that served this is the one beside the test binary (or $IRIS_OIIO_MODULE).
    EXPECT_EQ(oiioModule(p, "test").path, oiioModulePath());
    EXPECT_TRUE(fs::exists(oiioModulePath())) << oiioModulePath();
    // Four channels keep their names (values: OpenImageIO's alpha handling, as before the module).
    writeLDR(file("a.png"), Image(2, 2, 4));
    EXPECT_EQ(readImage(file("a.png")).channelNames, (std::vector<std::string>{"R", "G", "B", "A"}));
    writeLDR(file("a.jpg"), Image(2, 2, 4));
    EXPECT_EQ(readImage(file("a.jpg")).channels, 3);
}
