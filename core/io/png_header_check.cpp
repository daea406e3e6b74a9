#include "core/io/png_header_check.h"

#include <algorithm>
#include <cstdint>
#include <fstream>

#include "core/error.h"

namespace iris {

void checkPngChunkLengths(const std::string& path) {
    std::ifstream f(path, std::ios::binary | std::ios::ate);
    if (!f) return;  // the reader reports unreadable files
    const uint64_t size = uint64_t(f.tellg());
    f.seekg(0);
    static const unsigned char kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    unsigned char sig[8];
    if (!f.read(reinterpret_cast<char*>(sig), 8) || !std::equal(sig, sig + 8, kSignature)) return;
    uint64_t pos = 8;
    while (pos + 8 <= size) {
        unsigned char head[8];
        if (!f.read(reinterpret_cast<char*>(head), 8)) return;
        const uint64_t length = (uint64_t(head[0]) << 24) | (uint64_t(head[1]) << 16) | (uint64_t(head[2]) << 8) | head[3];
        const std::string type(reinterpret_cast<const char*>(head + 4), 4);
        const uint64_t left = size - pos - 8;
        if (length + 4 > left)  // data and CRC
            fail(path, ": corrupt PNG: chunk '", type, "' claims ", length, " bytes, ", left < 4 ? 0 : left - 4, " are left");
        if (type == "IEND") return;
        pos += 12 + length;
        f.seekg(std::streamoff(pos));
    }
}

}  // namespace iris
