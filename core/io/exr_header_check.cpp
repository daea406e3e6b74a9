// OpenEXR header size check (core/io/exr_header_check.h).
#include "core/io/exr_header_check.h"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>

#include "core/error.h"

namespace iris {

namespace {

constexpr unsigned char kExrMagic[4] = {0x76, 0x2f, 0x31, 0x01};
constexpr uint32_t kMultiPartFlag = 0x1000;
constexpr size_t kMaxNameLength = 255;  // long-name files; short-name files allow 31

/// A NUL-terminated string of at most kMaxNameLength characters ("" at the end of a list).
std::string readName(std::istream& in, const std::string& path) {
    std::string s;
    for (char c; in.get(c);) {
        if (c == '\0') return s;
        if (s.size() == kMaxNameLength) fail(path, ": corrupt EXR header: attribute name longer than ", kMaxNameLength, " bytes");
        s += c;
    }
    fail(path, ": corrupt EXR header: truncated attribute list");
}

constexpr uint64_t kMaxBufferBytes = uint64_t(1) << 30;

/// Scan lines per block of OpenEXR's compression codes 0-9 (NONE, RLE, ZIPS, ZIP, PIZ, PXR24, B44,
/// B44A, DWAA, DWAB; OpenEXR file layout, "Compression"); an unknown code counts as the largest.
uint64_t linesPerBlock(int compression) {
    static const uint64_t kLines[] = {1, 1, 1, 16, 32, 16, 32, 32, 32, 256};
    return compression >= 0 && compression < int(std::size(kLines)) ? kLines[compression] : 256;
}

/// Value sizes of OpenEXR 3.1's fixed-size attribute types (ImfStandardAttributes, Imf*Attribute),
/// which it reads whatever size the header declares; 0 for other types.
int fixedSize(const std::string& type) {
    static const std::pair<const char*, int> kSizes[] = {
        {"box2i", 16}, {"box2f", 16}, {"chromaticities", 32}, {"compression", 1}, {"double", 8},
        {"envmap", 1}, {"float", 4}, {"int", 4}, {"keycode", 28}, {"lineOrder", 1}, {"m33f", 36},
        {"m33d", 72}, {"m44f", 64}, {"m44d", 128}, {"rational", 8}, {"tiledesc", 9}, {"timecode", 8},
        {"v2i", 8}, {"v2f", 8}, {"v2d", 16}, {"v3i", 12}, {"v3f", 12}, {"v3d", 24}, {"deepImageState", 1}};
    for (const auto& [name, size] : kSizes)
        if (type == name) return size;
    return 0;
}

/// Skip a channel list as OpenEXR reads it: per channel a name, then 16 bytes (type, pLinear,
/// reserved, sampling), up to an empty name. Returns the channel count.
uint64_t skipChannelList(std::istream& in, const std::string& path) {
    uint64_t n = 0;
    while (!readName(in, path).empty()) {
        in.seekg(16, std::ios::cur);
        ++n;
    }
    return n;
}

/// What one header says that sizes OpenEXR's buffers.
struct BufferClaims {
    uint64_t channels = 0;
    int compression = 3;  // ZIP: OpenEXR's Header default, kept when no attribute is named "compression"
    std::string dataWindow;  // box2i: 16 bytes when present
    uint32_t tileX = 0, tileY = 0;  // tiledesc "tiles", 0 for scan-line parts
};

/// OpenEXR allocates its compressor buffers when it opens a file, before it reads a pixel, from the
/// header alone: for scan lines a block of linesPerBlock(compression) lines of the data window's
/// width, whatever the window's height; for tiles one tile of the declared tile size. Each such
/// buffer (at most 4 bytes a channel sample, and B44/PIZ keep a second buffer of twice that) must
/// stay below 1 GB, and the data window below `maxPixels`. Found by fuzz_image: a 700-byte file
/// claimed 7667716 x 769 pixels (tests/fuzz/corpus/image/oom-exr-data-window); a 659-byte file
/// allocated a compressor block of many more lines than its window had (that input was lost; the
/// corpus holds oom-exr-compressor-lines, a one-line window with PIZ's 32-line block, and
/// oom-exr-tile-size, a 2^32-pixel tile).
void checkBuffers(const BufferClaims& c, uint64_t maxPixels, const std::string& path) {
    if (c.dataWindow.size() != 16) return;  // OpenEXR refuses a header without one
    int32_t b[4];
    std::memcpy(b, c.dataWindow.data(), 16);
    const int64_t w = int64_t(b[2]) - b[0] + 1, h = int64_t(b[3]) - b[1] + 1;
    if (w <= 0 || h <= 0) fail(path, ": corrupt EXR header: empty data window");
    if (uint64_t(w) * uint64_t(h) > maxPixels)
        fail(path, ": image of ", w, "x", h, " pixels exceeds the limit of 2^", std::countr_zero(maxPixels), " pixels");
    const uint64_t sampleBytes = std::max<uint64_t>(c.channels, 1) * 4 * 2;  // 4 bytes, twice (see above)
    if (c.tileX > 0 || c.tileY > 0) {
        if (uint64_t(c.tileX) * uint64_t(c.tileY) * sampleBytes > kMaxBufferBytes)
            fail(path, ": EXR tiles of ", c.tileX, "x", c.tileY, " pixels with ", c.channels, " channels need more than 1 GB per tile");
        return;
    }
    if (uint64_t(w) * linesPerBlock(c.compression) * sampleBytes > kMaxBufferBytes)
        fail(path, ": EXR data window ", w, "x", h, " with ", c.channels, " channels needs more than 1 GB per block of ",
             linesPerBlock(c.compression), " scan lines");
}

/// Skip one header's attributes; false if the header is empty (the end of a multi-part list).
bool skipHeader(std::istream& in, uint64_t fileSize, uint64_t maxPixels, const std::string& path) {
    bool any = false;
    BufferClaims claims;
    for (;;) {
        const std::string name = readName(in, path);
        if (name.empty()) {
            checkBuffers(claims, maxPixels, path);
            return any;
        }
        any = true;
        const std::string type = readName(in, path);
        int32_t size = 0;
        if (!in.read(reinterpret_cast<char*>(&size), 4)) fail(path, ": corrupt EXR header: truncated attribute '", name, "'");
        const uint64_t left = fileSize - uint64_t(in.tellg());
        if (size < 0 || uint64_t(size) > left)
            fail(path, ": corrupt EXR header: attribute '", name, "' (", type, ") claims ", size, " bytes, the file has ", left, " left");
        const uint64_t at = uint64_t(in.tellg());
        if (type == "chlist") {
            // OpenEXR reads a channel list up to its terminator, whatever the declared size.
            claims.channels = skipChannelList(in, path);
        } else if (type == "preview") {
            // OpenEXR allocates width * height * 4 bytes for a preview image.
            uint32_t wh[2] = {0, 0};
            if (!in.read(reinterpret_cast<char*>(wh), 8)) fail(path, ": corrupt EXR header: truncated preview");
            if (uint64_t(wh[0]) * wh[1] * 4 > fileSize - at - 8)
                fail(path, ": corrupt EXR header: preview of ", wh[0], "x", wh[1], " pixels is larger than the file");
            in.seekg(std::streamoff(uint64_t(wh[0]) * wh[1] * 4), std::ios::cur);
        } else if (const int fixed = fixedSize(type); fixed > 0) {
            // OpenEXR reads a fixed-size value's own size, whatever the declared size.
            if (uint64_t(fixed) > left) fail(path, ": corrupt EXR header: truncated attribute '", name, "'");
            if (name == "dataWindow" && type == "box2i") {
                claims.dataWindow.resize(16);
                in.read(claims.dataWindow.data(), 16);
            } else if (name == "compression" && type == "compression") {
                claims.compression = in.get();
            } else if (name == "tiles" && type == "tiledesc") {
                uint32_t xy[2] = {0, 0};
                in.read(reinterpret_cast<char*>(xy), 8);
                in.seekg(1, std::ios::cur);  // level and rounding mode
                claims.tileX = xy[0];
                claims.tileY = xy[1];
            } else {
                in.seekg(fixed, std::ios::cur);
            }
        } else {
            in.seekg(size, std::ios::cur);  // string, vectors, unknown (opaque) types: the declared size
        }
        if (!in) fail(path, ": corrupt EXR header: truncated attribute '", name, "'");
    }
}

}  // namespace

bool hasExrMagic(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    unsigned char magic[4] = {};
    return in.read(reinterpret_cast<char*>(magic), 4) && std::memcmp(magic, kExrMagic, 4) == 0;
}

void checkExrHeaderSizes(const std::string& path, uint64_t maxPixels) {
    if (!hasExrMagic(path)) return;
    std::ifstream in(path, std::ios::binary | std::ios::ate);
    const uint64_t fileSize = uint64_t(in.tellg());
    in.seekg(4);
    uint32_t version = 0;
    if (!in.read(reinterpret_cast<char*>(&version), 4)) fail(path, ": corrupt EXR header: truncated version field");
    if (!(version & kMultiPartFlag)) {
        skipHeader(in, fileSize, maxPixels, path);
        return;
    }
    while (skipHeader(in, fileSize, maxPixels, path)) {
    }
}

}  // namespace iris
