// OpenEXR header size check (core/io/exr_header_check.h).
#include "core/io/exr_header_check.h"

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

/// Skip one header's attributes; false if the header is empty (the end of a multi-part list).
bool skipHeader(std::istream& in, uint64_t fileSize, const std::string& path) {
    bool any = false;
    for (;;) {
        const std::string name = readName(in, path);
        if (name.empty()) return any;
        any = true;
        const std::string type = readName(in, path);
        int32_t size = 0;
        if (!in.read(reinterpret_cast<char*>(&size), 4)) fail(path, ": corrupt EXR header: truncated attribute '", name, "'");
        const uint64_t left = fileSize - uint64_t(in.tellg());
        if (size < 0 || uint64_t(size) > left)
            fail(path, ": corrupt EXR header: attribute '", name, "' (", type, ") claims ", size, " bytes, the file has ", left, " left");
        in.seekg(size, std::ios::cur);
    }
}

}  // namespace

bool hasExrMagic(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    unsigned char magic[4] = {};
    return in.read(reinterpret_cast<char*>(magic), 4) && std::memcmp(magic, kExrMagic, 4) == 0;
}

void checkExrHeaderSizes(const std::string& path) {
    if (!hasExrMagic(path)) return;
    std::ifstream in(path, std::ios::binary | std::ios::ate);
    const uint64_t fileSize = uint64_t(in.tellg());
    in.seekg(4);
    uint32_t version = 0;
    if (!in.read(reinterpret_cast<char*>(&version), 4)) fail(path, ": corrupt EXR header: truncated version field");
    if (!(version & kMultiPartFlag)) {
        skipHeader(in, fileSize, path);
        return;
    }
    while (skipHeader(in, fileSize, path)) {
    }
}

}  // namespace iris
