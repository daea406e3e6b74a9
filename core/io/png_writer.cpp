#include "core/io/png_writer.h"

#include <array>
#include <cstdlib>

#include <zlib.h>

#include "core/error.h"

namespace iris {

namespace {

void putU32(std::vector<uint8_t>& out, uint32_t v) {
    for (int s = 24; s >= 0; s -= 8) out.push_back(uint8_t(v >> s));
}

/// One chunk: length, type, data, CRC-32 of type and data (PNG spec §5.3).
void putChunk(std::vector<uint8_t>& out, const char type[4], const std::vector<uint8_t>& data) {
    putU32(out, uint32_t(data.size()));
    const size_t start = out.size();
    out.insert(out.end(), type, type + 4);
    out.insert(out.end(), data.begin(), data.end());
    putU32(out, uint32_t(crc32(0L, out.data() + start, uInt(out.size() - start))));
}

/// Paeth predictor (PNG spec §9.4).
uint8_t paeth(int a, int b, int c) {
    const int p = a + b - c, pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
    return uint8_t(pa <= pb && pa <= pc ? a : pb <= pc ? b : c);
}

/// Filter one row with each of the five filter types (PNG spec §9.2) and keep the one with the
/// smallest sum of absolute (signed) differences, the heuristic the spec recommends (§12.8).
void filterRow(const uint8_t* row, const uint8_t* prev, size_t n, int bpp, std::vector<uint8_t>& out) {
    std::array<std::vector<uint8_t>, 5> f;
    std::array<uint64_t, 5> cost{};
    for (int t = 0; t < 5; ++t) {
        f[t].resize(n);
        for (size_t i = 0; i < n; ++i) {
            const int a = i >= size_t(bpp) ? row[i - bpp] : 0, b = prev ? prev[i] : 0;
            const int c = prev && i >= size_t(bpp) ? prev[i - bpp] : 0;
            const int pred = t == 0 ? 0 : t == 1 ? a : t == 2 ? b : t == 3 ? (a + b) / 2 : paeth(a, b, c);
            f[t][i] = uint8_t(row[i] - pred);
            cost[t] += uint64_t(std::abs(int(int8_t(f[t][i]))));
        }
    }
    int best = 0;
    for (int t = 1; t < 5; ++t)
        if (cost[t] < cost[best]) best = t;
    out.push_back(uint8_t(best));
    out.insert(out.end(), f[best].begin(), f[best].end());
}

}  // namespace

std::vector<uint8_t> encodePNG(int width, int height, int channels, const uint8_t* pixels) {
    if (width <= 0 || height <= 0) fail("PNG: image size must be positive, got ", width, "x", height);
    if (channels < 1 || channels > 4) fail("PNG: 1 to 4 channels, got ", channels);
    static constexpr uint8_t kColourType[5] = {0, 0, 4, 2, 6};  // by channel count (§11.2.2)
    const size_t rowBytes = size_t(width) * size_t(channels);
    std::vector<uint8_t> raw;
    raw.reserve((rowBytes + 1) * size_t(height));
    for (int y = 0; y < height; ++y)
        filterRow(pixels + size_t(y) * rowBytes, y > 0 ? pixels + size_t(y - 1) * rowBytes : nullptr, rowBytes, channels, raw);

    uLongf zsize = compressBound(uLong(raw.size()));
    std::vector<uint8_t> idat(zsize);
    if (compress2(idat.data(), &zsize, raw.data(), uLong(raw.size()), Z_DEFAULT_COMPRESSION) != Z_OK)
        fail("PNG: zlib compression failed");
    idat.resize(zsize);

    std::vector<uint8_t> ihdr;
    putU32(ihdr, uint32_t(width));
    putU32(ihdr, uint32_t(height));
    ihdr.insert(ihdr.end(), {8, kColourType[channels], 0, 0, 0});  // depth, colour type, deflate, filter 0, no interlace

    std::vector<uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};  // signature (§5.2)
    putChunk(png, "IHDR", ihdr);
    putChunk(png, "IDAT", idat);
    putChunk(png, "IEND", {});
    return png;
}

}  // namespace iris
