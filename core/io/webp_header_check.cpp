#include "core/io/webp_header_check.h"

#include <cstdint>
#include <cstring>
#include <fstream>

namespace iris {

namespace {

using Bytes = const unsigned char*;

unsigned le16(Bytes b) { return unsigned(b[0]) | unsigned(b[1]) << 8; }
unsigned le24(Bytes b) { return le16(b) | unsigned(b[2]) << 16; }

/// A VP8L bitstream (RFC 9649 §3.2.1): signature 0x2f, then width − 1 and height − 1 in 14 bits
/// each, an alpha bit and a 3-bit version that must be 0. Needs 5 bytes.
std::optional<WebpCanvas> vp8l(Bytes b, size_t n) {
    if (n < 5 || b[0] != 0x2f || (b[4] >> 5) != 0) return std::nullopt;
    const unsigned bits = unsigned(b[1]) | unsigned(b[2]) << 8 | unsigned(b[3]) << 16 | unsigned(b[4]) << 24;
    return WebpCanvas{1 + (long long)(bits & 0x3fff), 1 + (long long)((bits >> 14) & 0x3fff)};
}

/// A VP8 key frame (RFC 6386 §9.1): a 3-byte frame tag, the start code 9d 01 2a, then width and
/// height in the low 14 bits of two little-endian 16-bit words (the top 2 bits are scaling).
std::optional<WebpCanvas> vp8(Bytes b, size_t n) {
    if (n < 10 || b[3] != 0x9d || b[4] != 0x01 || b[5] != 0x2a) return std::nullopt;
    return WebpCanvas{(long long)(le16(b + 6) & 0x3fff), (long long)(le16(b + 8) & 0x3fff)};
}

}  // namespace

std::optional<WebpCanvas> webpCanvas(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    if (!f) return std::nullopt;  // the reader reports unreadable files
    unsigned char b[32] = {};
    f.read(reinterpret_cast<char*>(b), sizeof(b));
    const size_t n = size_t(f.gcount());
    if (n >= 20 && std::memcmp(b, "RIFF", 4) == 0 && std::memcmp(b + 8, "WEBP", 4) == 0) {
        Bytes chunk = b + 12, payload = b + 20;
        const size_t left = n - 20;
        if (std::memcmp(chunk, "VP8X", 4) == 0 && left >= 10)  // RFC 9649 §2.7: flags, 3 reserved, sizes − 1
            return WebpCanvas{1 + (long long)le24(payload + 4), 1 + (long long)le24(payload + 7)};
        if (std::memcmp(chunk, "VP8L", 4) == 0) return vp8l(payload, left);
        if (std::memcmp(chunk, "VP8 ", 4) == 0) return vp8(payload, left);
        return std::nullopt;
    }
    if (auto c = vp8l(b, n)) return c;
    return vp8(b, n);
}

}  // namespace iris
