// OpenEXR header size check (core/io/exr_header_check.h).
#include "core/io/exr_header_check.h"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <fstream>

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

constexpr uint64_t kMaxBlockLines = 256;         // the most scan lines one block holds (DWAB)
constexpr uint64_t kMaxBlockBytes = uint64_t(1) << 30;

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

/// The data window (box2i) must not exceed `maxPixels`, and one block of scan lines of all
/// channels (at most 4 bytes each) must stay below 1 GB: OpenEXR allocates its decompression
/// buffer from these before reading any pixel (a 700-byte file claimed 7667716 x 769 pixels,
/// found by fuzz_image: tests/fuzz/corpus/image/oom-exr-data-window).
void checkDataWindow(const std::string& box, uint64_t channels, uint64_t maxPixels, const std::string& path) {
    int32_t b[4];
    std::memcpy(b, box.data(), 16);
    const int64_t w = int64_t(b[2]) - b[0] + 1, h = int64_t(b[3]) - b[1] + 1;
    if (w <= 0 || h <= 0) fail(path, ": corrupt EXR header: empty data window");
    if (uint64_t(w) * uint64_t(h) > maxPixels)
        fail(path, ": image of ", w, "x", h, " pixels exceeds the limit of 2^", std::countr_zero(maxPixels), " pixels");
    if (uint64_t(w) * std::min<uint64_t>(uint64_t(h), kMaxBlockLines) * std::max<uint64_t>(channels, 1) * 4 > kMaxBlockBytes)
        fail(path, ": EXR data window ", w, "x", h, " with ", channels, " channels needs more than 1 GB per block");
}

/// Skip one header's attributes; false if the header is empty (the end of a multi-part list).
bool skipHeader(std::istream& in, uint64_t fileSize, uint64_t maxPixels, const std::string& path) {
    bool any = false;
    uint64_t channels = 0;
    std::string dataWindow;
    for (;;) {
        const std::string name = readName(in, path);
        if (name.empty()) {
            if (dataWindow.size() == 16) checkDataWindow(dataWindow, channels, maxPixels, path);
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
            channels = skipChannelList(in, path);
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
                dataWindow.resize(16);
                in.read(dataWindow.data(), 16);
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
