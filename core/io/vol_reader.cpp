#include "core/io/vol_reader.h"

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

#include "core/error.h"
#include "core/input_file.h"
#include "core/memory_budget.h"

namespace iris {
namespace {

constexpr size_t kHeaderBytes = 48;  // 'VOL', version, encoding, 3 resolutions, channels, 6 floats
/// Values a file may hold (2^40 floats = 4 TiB): a bound on the header's product before it is
/// compared with the file length, so that no product can overflow.
constexpr uint64_t kMaxValues = uint64_t(1) << 40;

// Encodings of Mitsuba 0.6's EVolumeType (src/volume/gridvolume.cpp).
enum Encoding : int32_t { kFloat32 = 1, kFloat16 = 2, kUInt8 = 3, kQuantizedDirections = 4 };

uint32_t loadU32(const std::string& b, size_t at) {  // little endian, whatever the host
    uint32_t v = 0;
    for (int i = 3; i >= 0; --i) v = (v << 8) | uint8_t(b[at + size_t(i)]);
    return v;
}
int32_t loadI32(const std::string& b, size_t at) { return std::bit_cast<int32_t>(loadU32(b, at)); }
float loadF32(const std::string& b, size_t at) { return std::bit_cast<float>(loadU32(b, at)); }

struct Header {
    int32_t encoding = 0, res[3] = {0, 0, 0}, channels = 0;
    float box[6] = {0, 0, 0, 0, 0, 0};
    uint64_t values = 0;  // res[0]·res[1]·res[2]·channels
};

int bytesPerValue(int32_t encoding) { return encoding == kUInt8 ? 1 : 4; }

void checkMagic(const std::string& b, const std::string& name) {
    if (b.size() < 3 || b.compare(0, 3, "VOL") != 0) fail(name, ": not a .vol grid file (missing the 'VOL' magic)");
    if (b.size() < 4) fail(name, ": truncated .vol header (", b.size(), " bytes; the header has ", kHeaderBytes, ")");
    if (uint8_t(b[3]) != 3) fail(name, ": unsupported .vol version ", int(uint8_t(b[3])), " (only version 3 is supported)");
    if (b.size() < kHeaderBytes)
        fail(name, ": truncated .vol header (", b.size(), " bytes; the header has ", kHeaderBytes, ")");
}

void checkEncoding(int32_t e, const std::string& name) {
    if (e == kFloat32 || e == kUInt8) return;
    if (e == kFloat16) fail(name, ": .vol encoding 2 (float16) is not supported (supported: 1 = float32, 3 = uint8)");
    if (e == kQuantizedDirections)
        fail(name, ": .vol encoding 4 (quantized directions) is not supported (supported: 1 = float32, 3 = uint8)");
    fail(name, ": unknown .vol encoding ", e, " (supported: 1 = float32, 3 = uint8)");
}

/// The product of the resolutions and channels, each checked first; an error past kMaxValues.
uint64_t valueCount(const Header& h, const std::string& name) {
    for (int32_t r : h.res)
        if (r <= 0) fail(name, ": invalid .vol resolution ", h.res[0], "x", h.res[1], "x", h.res[2], " (each must be positive)");
    if (h.channels <= 0 || h.channels > kMaxVolChannels)
        fail(name, ": invalid .vol channel count ", h.channels, " (must be 1 to ", kMaxVolChannels, ")");
    uint64_t n = uint64_t(h.channels);
    for (int32_t r : h.res) {
        if (n > kMaxValues / uint64_t(r))  // n·r would pass the bound (and could overflow later)
            fail(name, ": .vol resolution ", h.res[0], "x", h.res[1], "x", h.res[2], " with ", h.channels,
                 " channels is too large (over 2^40 values)");
        n *= uint64_t(r);
    }
    return n;
}

Header parseHeader(const std::string& b, const std::string& name) {
    checkMagic(b, name);
    Header h;
    h.encoding = loadI32(b, 4);
    checkEncoding(h.encoding, name);
    for (int i = 0; i < 3; ++i) h.res[i] = loadI32(b, 8 + 4 * size_t(i));
    h.channels = loadI32(b, 20);
    h.values = valueCount(h, name);
    for (int i = 0; i < 6; ++i) {
        h.box[i] = loadF32(b, 24 + 4 * size_t(i));
        if (!std::isfinite(h.box[i])) fail(name, ": the .vol bounding box has a non-finite value (", h.box[i], ")");
    }
    // The data must be exactly what the header announces (before anything is allocated).
    const uint64_t want = h.values * uint64_t(bytesPerValue(h.encoding)), have = b.size() - kHeaderBytes;
    if (have < want)
        fail(name, ": truncated .vol data (", h.res[0], "x", h.res[1], "x", h.res[2], "x", h.channels, " values need ", want,
             " bytes after the header, the file has ", have, ")");
    if (have > want)
        fail(name, ": .vol size mismatch (", h.res[0], "x", h.res[1], "x", h.res[2], "x", h.channels, " values need ", want,
             " bytes after the header, the file has ", have - want, " more)");
    return h;
}

[[noreturn]] void failNonFinite(const Header& h, uint64_t i, float v, const std::string& name) {
    const uint64_t c = i % uint64_t(h.channels), voxel = i / uint64_t(h.channels);
    const uint64_t x = voxel % uint64_t(h.res[0]), y = voxel / uint64_t(h.res[0]) % uint64_t(h.res[1]);
    const uint64_t z = voxel / (uint64_t(h.res[0]) * uint64_t(h.res[1]));
    fail(name, ": non-finite .vol value ", v, " at voxel (", x, ", ", y, ", ", z, ") channel ", c);
}

}  // namespace

VolumeGridData parseVol(const std::string& b, const std::string& name) {
    const Header h = parseHeader(b, name);
    chargeMemory(h.values * sizeof(float), strCat(name, ": grid of ", h.res[0], "x", h.res[1], "x", h.res[2], "x",
                                                  h.channels, " floats (.vol header)"));
    VolumeGridData g;
    g.xres = h.res[0], g.yres = h.res[1], g.zres = h.res[2], g.channels = h.channels;
    g.bboxMin = vec3(h.box[0], h.box[1], h.box[2]);
    g.bboxMax = vec3(h.box[3], h.box[4], h.box[5]);
    g.values.resize(size_t(h.values));
    for (uint64_t i = 0; i < h.values; ++i) {
        // uint8 → v/255 (Mitsuba 0.6 gridvolume.cpp, lookups of EUInt8 data).
        const float v = h.encoding == kUInt8 ? float(uint8_t(b[kHeaderBytes + i])) / 255.0f
                                             : loadF32(b, kHeaderBytes + 4 * i);
        if (!std::isfinite(v)) failNonFinite(h, i, v, name);
        g.values[i] = v;
    }
    return g;
}

VolumeGridData readVolFile(const std::string& path) { return parseVol(readInputFile(path, ".vol grid file"), path); }

}  // namespace iris
