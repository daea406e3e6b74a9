// iris's PNG encoder (core/io/png_writer.h), checked against an independent decoder: OpenImageIO's
// PNG reader (libpng), which verifies every chunk CRC and undoes the five row filters.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>

#include "core/error.h"
#include "core/io/image.h"
#include "core/io/png_header_check.h"
#include "core/io/png_writer.h"
#include "tests/support/app_runner.h"

using namespace iris;

namespace {

std::string writeFile(const std::string& name, const std::vector<uint8_t>& bytes) {
    const std::string p = iris::testing::tempPath("iris_png", name);
    std::ofstream(p, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    return p;
}

/// Noise plus gradients, so that every filter type wins on some rows.
std::vector<uint8_t> testPixels(int w, int h, int c) {
    std::mt19937 rng(7);
    std::vector<uint8_t> px(size_t(w) * size_t(h) * size_t(c));
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int k = 0; k < c; ++k) {
                const size_t i = (size_t(y) * size_t(w) + size_t(x)) * size_t(c) + size_t(k);
                const bool alpha = (c == 2 || c == 4) && k == c - 1;
                // Opaque alpha: OpenImageIO's reader premultiplies colour by alpha.
                px[i] = alpha ? 255 : y % 3 == 0 ? uint8_t(rng()) : uint8_t(x * 5 + y * 3 + k * 40);
            }
    return px;
}

}  // namespace

TEST(PngWriter, EveryChannelCountDecodesToTheSameBytes) {
    for (int c = 1; c <= 4; ++c) {
        const int w = 37, h = 23;
        const std::vector<uint8_t> px = testPixels(w, h, c);
        const std::string p = writeFile("c" + std::to_string(c) + ".png", encodePNG(w, h, c, px.data()));
        const Image img = readImage(p);
        ASSERT_EQ(img.width, w);
        ASSERT_EQ(img.height, h);
        ASSERT_EQ(img.channels, c);
        for (size_t i = 0; i < px.size(); ++i)
            ASSERT_EQ(int(std::lround(img.pixels[i] * 255.0f)), int(px[i])) << "channels " << c << " value " << i;
        std::filesystem::remove(p);
    }
}

TEST(PngWriter, ACorruptedByteIsCaughtByTheDecoder) {
    // The round trip above means something only if the decoder checks: flip one byte of the image
    // data and libpng must refuse the file (CRC mismatch).
    const std::vector<uint8_t> px = testPixels(16, 16, 3);
    std::vector<uint8_t> png = encodePNG(16, 16, 3, px.data());
    png[png.size() - 20] ^= 0x5a;  // inside IDAT (IEND is the last 12 bytes)
    const std::string p = writeFile("corrupt.png", png);
    EXPECT_THROW(readImage(p), Error);
    std::filesystem::remove(p);
}

TEST(PngWriter, SmoothImagesCompressAndBadShapesAreRejected) {
    std::vector<uint8_t> flat(size_t(256) * 256 * 3, 128);
    EXPECT_LT(encodePNG(256, 256, 3, flat.data()).size(), 2000u);  // 196 kB of one value
    EXPECT_THROW(encodePNG(4, 4, 5, flat.data()), Error);
    EXPECT_THROW(encodePNG(0, 4, 3, flat.data()), Error);
}

TEST(PngWriter, WriteLdrPngIsTheEncodersFile) {
    Image img(5, 3, 3);
    for (size_t i = 0; i < img.pixels.size(); ++i) img.pixels[i] = float(i) / float(img.pixels.size());
    const std::string p = iris::testing::tempPath("iris_png", "ldr.png");
    writeLDR(p, img);
    std::ifstream f(p, std::ios::binary);
    char sig[8];
    f.read(sig, 8);
    EXPECT_EQ(std::string(sig + 1, 3), "PNG");
    const Image back = readImage(p);
    for (size_t i = 0; i < img.pixels.size(); ++i) EXPECT_EQ(int(std::lround(back.pixels[i] * 255.0f)), int(std::lround(img.pixels[i] * 255.0f)));
    std::filesystem::remove(p);
}

TEST(PngHeaderCheck, AChunkClaimingMoreThanTheFileIsRefusedBeforeDecoding) {
    const std::vector<uint8_t> px = testPixels(8, 8, 3);
    std::vector<uint8_t> png = encodePNG(8, 8, 3, px.data());
    const std::string ok = writeFile("ok.png", png);
    EXPECT_NO_THROW(checkPngChunkLengths(ok));
    png[33] = 0x7f;  // the IDAT chunk's length (after the 8-byte signature and the 25-byte IHDR chunk)
    const std::string bad = writeFile("claims.png", png);
    try {
        checkPngChunkLengths(bad);
        FAIL() << "a chunk claiming ~2 GB was accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("chunk 'IDAT' claims"), std::string::npos) << e.what();
    }
    EXPECT_THROW(readImage(bad), Error);
    std::filesystem::remove(ok);
    std::filesystem::remove(bad);
}
