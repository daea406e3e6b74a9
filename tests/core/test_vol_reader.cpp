// The .vol grid reader (core/io/vol_reader.h): files written by the test into a temporary folder
// read back exactly; every malformed header, a truncated or padded body, non-finite values, a
// missing file and a grid over the memory limit are rejected with a message naming the file and
// the problem.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>

#include "core/io/vol_reader.h"
#include "core/memory_budget.h"
#include "tests/support/error_of.h"

namespace iris {
namespace {

using test::errorOf;

struct VolHeader {
    std::string magic = "VOL";
    int version = 3;
    int32_t encoding = 1, xres = 2, yres = 3, zres = 4, channels = 1;
    float box[6] = {-1, -2, -3, 1, 2, 3};
};

void putI32(std::string& s, int32_t v) {
    for (int i = 0; i < 4; ++i) s.push_back(char(uint32_t(v) >> (8 * i) & 0xff));
}
void putF32(std::string& s, float v) {
    uint32_t u;
    std::memcpy(&u, &v, 4);
    putI32(s, int32_t(u));
}

std::string header(const VolHeader& h) {
    std::string s = h.magic;
    s.push_back(char(h.version));
    for (int32_t v : {h.encoding, h.xres, h.yres, h.zres, h.channels}) putI32(s, v);
    for (float f : h.box) putF32(s, f);
    return s;
}

std::string floatFile(const VolHeader& h, const std::vector<float>& values) {
    std::string s = header(h);
    for (float v : values) putF32(s, v);
    return s;
}

class VolReader : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = std::filesystem::temp_directory_path() /
               ("iris_vol_reader_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "_" +
                ::testing::UnitTest::GetInstance()->current_test_info()->name());
        std::filesystem::create_directories(dir_);
    }
    void TearDown() override { std::filesystem::remove_all(dir_); }

    std::string write(const std::string& name, const std::string& bytes) {
        const std::string path = (dir_ / name).string();
        std::ofstream(path, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
        return path;
    }
    /// The message of reading these bytes from a file; it must name the file.
    std::string errorReading(const std::string& bytes) {
        const std::string path = write("bad.vol", bytes);
        const std::string msg = errorOf([&] { readVolFile(path); });
        EXPECT_NE(msg.find(path), std::string::npos) << msg;
        return msg;
    }

    std::filesystem::path dir_;
};

std::vector<float> ramp(size_t n) {
    std::vector<float> v(n);
    for (size_t i = 0; i < n; ++i) v[i] = 0.25f * float(i) - 1.0f;
    return v;
}

TEST_F(VolReader, Float32RoundTrip) {
    VolHeader h;
    const std::vector<float> values = ramp(2 * 3 * 4);
    const VolumeGridData g = readVolFile(write("a.vol", floatFile(h, values)));
    EXPECT_EQ(g.xres, 2);
    EXPECT_EQ(g.yres, 3);
    EXPECT_EQ(g.zres, 4);
    EXPECT_EQ(g.channels, 1);
    EXPECT_EQ(g.bboxMin, vec3(-1, -2, -3));
    EXPECT_EQ(g.bboxMax, vec3(1, 2, 3));
    ASSERT_EQ(g.values, values);
    // ((z·yres + y)·xres + x)·channels + c
    EXPECT_EQ(g.at(1, 2, 3, 0), values[(3 * 3 + 2) * 2 + 1]);
    EXPECT_EQ(g.at(1, 0, 0, 0), values[1]);
}

TEST_F(VolReader, ThreeChannelIndexing) {
    VolHeader h;
    h.xres = 3, h.yres = 1, h.zres = 2, h.channels = 3;
    const std::vector<float> values = ramp(3 * 2 * 3);
    const VolumeGridData g = readVolFile(write("rgb.vol", floatFile(h, values)));
    EXPECT_EQ(g.at(2, 0, 1, 1), values[((1 * 1 + 0) * 3 + 2) * 3 + 1]);
}

TEST_F(VolReader, UInt8IsScaledBy255) {
    VolHeader h;
    h.encoding = 3, h.xres = 4, h.yres = 1, h.zres = 1;
    std::string s = header(h);
    for (int v : {0, 51, 128, 255}) s.push_back(char(v));
    const VolumeGridData g = readVolFile(write("u8.vol", s));
    ASSERT_EQ(g.values.size(), 4u);
    EXPECT_FLOAT_EQ(g.values[0], 0.0f);
    EXPECT_FLOAT_EQ(g.values[1], 0.2f);
    EXPECT_FLOAT_EQ(g.values[2], 128.0f / 255.0f);
    EXPECT_FLOAT_EQ(g.values[3], 1.0f);
}

TEST_F(VolReader, MissingFileNamesIt) {
    const std::string path = (dir_ / "nope.vol").string();
    const std::string msg = errorOf([&] { readVolFile(path); });
    EXPECT_NE(msg.find(path), std::string::npos) << msg;
    EXPECT_NE(msg.find("cannot open"), std::string::npos) << msg;
}

TEST_F(VolReader, RejectsBadMagicAndVersion) {
    VolHeader h;
    EXPECT_NE(errorReading("").find("missing the 'VOL' magic"), std::string::npos);
    h.magic = "VOX";
    EXPECT_NE(errorReading(floatFile(h, ramp(24))).find("missing the 'VOL' magic"), std::string::npos);
    h = VolHeader();
    h.version = 2;
    EXPECT_NE(errorReading(floatFile(h, ramp(24))).find("unsupported .vol version 2"), std::string::npos);
    EXPECT_NE(errorReading("VOL").find("truncated .vol header"), std::string::npos);
    EXPECT_NE(errorReading(header(VolHeader()).substr(0, 30)).find("truncated .vol header (30 bytes"),
              std::string::npos);
}

TEST_F(VolReader, RejectsUnsupportedEncodings) {
    VolHeader h;
    h.encoding = 2;
    EXPECT_NE(errorReading(floatFile(h, ramp(24))).find("encoding 2 (float16) is not supported"), std::string::npos);
    h.encoding = 4;
    EXPECT_NE(errorReading(floatFile(h, ramp(24))).find("encoding 4 (quantized directions) is not supported"),
              std::string::npos);
    h.encoding = 9;
    EXPECT_NE(errorReading(floatFile(h, ramp(24))).find("unknown .vol encoding 9"), std::string::npos);
}

TEST_F(VolReader, RejectsBadResolutionsAndChannels) {
    for (int32_t bad : {0, -1, std::numeric_limits<int32_t>::min()}) {
        VolHeader h;
        h.yres = bad;
        EXPECT_NE(errorReading(floatFile(h, ramp(24))).find("invalid .vol resolution"), std::string::npos) << bad;
    }
    for (int32_t bad : {0, -3, kMaxVolChannels + 1}) {
        VolHeader h;
        h.channels = bad;
        EXPECT_NE(errorReading(floatFile(h, ramp(24))).find("invalid .vol channel count"), std::string::npos) << bad;
    }
    // 2^31−1 per axis: the product overflows 64 bits; it is refused before any allocation.
    VolHeader h;
    h.xres = h.yres = h.zres = std::numeric_limits<int32_t>::max();
    h.channels = kMaxVolChannels;
    EXPECT_NE(errorReading(floatFile(h, ramp(4))).find("too large"), std::string::npos);
    // A large but representable header is compared with the file length, not allocated.
    h.xres = h.yres = 4096, h.zres = 1024, h.channels = 1;
    EXPECT_NE(errorReading(floatFile(h, ramp(4))).find("truncated .vol data"), std::string::npos);
}

TEST_F(VolReader, RejectsTruncatedAndPaddedData) {
    VolHeader h;
    std::string full = floatFile(h, ramp(24));
    const std::string msg = errorReading(full.substr(0, full.size() - 3));
    EXPECT_NE(msg.find("truncated .vol data"), std::string::npos) << msg;
    EXPECT_NE(msg.find("need 96 bytes"), std::string::npos) << msg;
    EXPECT_NE(errorReading(full + "xy").find(".vol size mismatch"), std::string::npos);
    h.encoding = 3;  // uint8: one byte per value
    EXPECT_NE(errorReading(header(h) + std::string(23, '\1')).find("truncated .vol data"), std::string::npos);
}

TEST_F(VolReader, RejectsNonFiniteValues) {
    VolHeader h;
    std::vector<float> v = ramp(24);
    v[(2 * 3 + 1) * 2 + 1] = std::numeric_limits<float>::quiet_NaN();  // voxel (1, 1, 2)
    const std::string msg = errorReading(floatFile(h, v));
    EXPECT_NE(msg.find("non-finite .vol value"), std::string::npos) << msg;
    EXPECT_NE(msg.find("voxel (1, 1, 2)"), std::string::npos) << msg;
    v = ramp(24);
    v[0] = std::numeric_limits<float>::infinity();
    EXPECT_NE(errorReading(floatFile(h, v)).find("non-finite"), std::string::npos);
    h.box[4] = std::numeric_limits<float>::infinity();
    EXPECT_NE(errorReading(floatFile(h, ramp(24))).find("bounding box has a non-finite value"), std::string::npos);
}

TEST_F(VolReader, ChargesTheMemoryBudgetFromTheHeader) {
    VolHeader h;
    h.xres = 64, h.yres = 64, h.zres = 16;  // 256 KiB of floats
    const std::string bytes = floatFile(h, std::vector<float>(64 * 64 * 16, 0.5f));
    setMemoryLimit(200 * 1024);
    const std::string msg = errorOf([&] { parseVol(bytes, "big.vol"); });
    setMemoryLimit(0);
    EXPECT_NE(msg.find("big.vol: grid of 64x64x16x1 floats"), std::string::npos) << msg;
    EXPECT_NE(msg.find("memory limit"), std::string::npos) << msg;
    EXPECT_EQ(parseVol(bytes, "big.vol").values.size(), size_t(64 * 64 * 16));
}

}  // namespace
}  // namespace iris
