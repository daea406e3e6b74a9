// The WebP canvas check before OpenImageIO opens a file (core/io/webp_header_check.h): the sizes
// of every form libwebp decodes are read as the specifications place them, and a header claiming
// more pixels than its file can hold is refused before OpenImageIO allocates them.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "core/io/image.h"
#include "core/io/webp_header_check.h"
#include "tests/support/app_runner.h"

using namespace iris;

namespace {

std::string writeFile(const std::string& name, const std::vector<uint8_t>& bytes) {
    const std::string p = iris::testing::tempPath("iris_webp", name);
    std::ofstream(p, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    return p;
}

/// A lossy 5x3 orange WebP ("RIFF....WEBPVP8 "), written by `oiiotool --pattern
/// constant:color=1,0.5,0 5x3 3 -o t.webp` (OpenImageIO 2.4, libwebp).
const std::vector<uint8_t> kOrange5x3 = {
    0x52, 0x49, 0x46, 0x46, 0x44, 0x00, 0x00, 0x00, 0x57, 0x45, 0x42, 0x50, 0x56, 0x50, 0x38, 0x20, 0x38, 0x00, 0x00,
    0x00, 0x50, 0x02, 0x00, 0x9d, 0x01, 0x2a, 0x05, 0x00, 0x03, 0x00, 0x00, 0x00, 0x00, 0x25, 0xa0, 0x02, 0x74, 0xba,
    0x01, 0xf8, 0x01, 0xfa, 0x01, 0xfc, 0x00, 0x07, 0x90, 0x00, 0xfe, 0xfb, 0xa7, 0xab, 0xff, 0xef, 0x11, 0xa8, 0x0e,
    0xde, 0xa3, 0x7f, 0xfb, 0xc4, 0x6f, 0xff, 0xd1, 0x9f, 0x38, 0x6d, 0x12, 0x23, 0xff, 0xf4, 0x5d, 0x80, 0x00, 0x00};

void expectRefused(const std::string& path, const char* why) {
    try {
        readImage(path);
        FAIL() << why << " was read";
    } catch (const Error& e) {
        const std::string msg = e.what();
        EXPECT_NE(msg.find(path), std::string::npos) << msg;
        EXPECT_NE(msg.find("more than a"), std::string::npos) << msg;
    }
}

}  // namespace

TEST(WebpHeaderCheck, AWebpFileIsMeasuredAndStillRead) {
    const std::string p = writeFile("orange.webp", kOrange5x3);
    const auto canvas = webpCanvas(p);
    ASSERT_TRUE(canvas);
    EXPECT_EQ(canvas->width, 5);
    EXPECT_EQ(canvas->height, 3);
    const Image img = readImage(p);
    EXPECT_EQ(img.width, 5);
    EXPECT_EQ(img.height, 3);
    std::filesystem::remove(p);
}

TEST(WebpHeaderCheck, OtherFilesHaveNoCanvas) {
    const std::string p = writeFile("text.txt", {'h', 'e', 'l', 'l', 'o', ' ', 'w', 'e', 'b', 'p'});
    EXPECT_FALSE(webpCanvas(p));
    std::filesystem::remove(p);
}

TEST(WebpHeaderCheck, EveryFormLibwebpDecodesIsMeasured) {
    // VP8X (RFC 9649 §2.7): flags, 3 reserved bytes, canvas width − 1 and height − 1 in 24 bits.
    std::vector<uint8_t> vp8x = {'R', 'I', 'F', 'F', 30, 0, 0, 0, 'W', 'E', 'B', 'P', 'V', 'P', '8', 'X', 10, 0, 0, 0,
                                 0x10, 0, 0, 0, 0x0f, 0x27, 0x00, 0x1f, 0x4e, 0x00};
    const std::string px = writeFile("vp8x.webp", vp8x);
    ASSERT_TRUE(webpCanvas(px));
    EXPECT_EQ(webpCanvas(px)->width, 10000);     // 0x00270f + 1
    EXPECT_EQ(webpCanvas(px)->height, 20000);    // 0x004e1f + 1
    expectRefused(px, "a 30-byte VP8X file claiming 10000 x 20000 pixels");
    // A bare VP8L bitstream (RFC 9649 §3.2.1), the fuzz finding: 12761 x 12401 pixels, 633 MB
    // allocated by OpenImageIO's open() before this check.
    std::vector<uint8_t> vp8l = {0x2f, 0xd8, 0x31, 0x1c, 0x1c};
    vp8l.resize(600, 0x1c);
    const std::string pl = writeFile("bare.vp8l", vp8l);
    ASSERT_TRUE(webpCanvas(pl));
    EXPECT_EQ(webpCanvas(pl)->width, 12761);
    EXPECT_EQ(webpCanvas(pl)->height, 12401);
    expectRefused(pl, "a 600-byte VP8L bitstream claiming 12761 x 12401 pixels");
    // A VP8L stream with a version other than 0 is not one.
    vp8l[4] = 0x3c;
    const std::string pv = writeFile("version.vp8l", vp8l);
    EXPECT_FALSE(webpCanvas(pv));
    // A bare VP8 key frame (RFC 6386 §9.1) after the container is taken away.
    const std::vector<uint8_t> bare(kOrange5x3.begin() + 20, kOrange5x3.end());
    const std::string pb = writeFile("bare.vp8", bare);
    ASSERT_TRUE(webpCanvas(pb));
    EXPECT_EQ(webpCanvas(pb)->width, 5);
    EXPECT_EQ(webpCanvas(pb)->height, 3);
    for (const std::string& p : {px, pl, pv, pb}) std::filesystem::remove(p);
}
