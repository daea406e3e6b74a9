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

/// Channels in a "chlist" value: per channel a name, then 16 bytes (type, pLinear, sampling).
uint64_t channelCount(const std::string& v) {
    uint64_t n = 0;
    for (size_t at = 0; at < v.size() && v[at] != '\0'; ++n) {
        const size_t end = v.find('\0', at);
        if (end == std::string::npos) break;
        at = end + 1 + 16;
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
        if ((name == "channels" && type == "chlist") || (name == "dataWindow" && type == "box2i")) {
            std::string value(size_t(size), '\0');
            if (!in.read(value.data(), size)) fail(path, ": corrupt EXR header: truncated attribute '", name, "'");
            if (name == "channels") channels = channelCount(value);
            else dataWindow = value;
        } else {
            in.seekg(size, std::ios::cur);
        }
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
