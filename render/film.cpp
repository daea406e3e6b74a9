#include "render/film.h"

#include <zlib.h>

#include <algorithm>
#include <cstdio>
#include <cstring>

#include "core/error.h"
#include "core/input_file.h"
#include "core/io/atomic_file.h"

namespace iris {

Film::Film(int width, int height) : width_(width), height_(height) {
    if (width <= 0 || height <= 0) fail("film size must be positive, got ", width, "x", height);
    const uint64_t n = uint64_t(width) * uint64_t(height);
    if (n > (uint64_t(1) << 28)) fail("film of ", width, "x", height, " pixels is too large (limit 2^28 pixels)");
    sum_.assign(3 * n, 0);
    sumSq_.assign(3 * n, 0.0);
    count_.assign(n, 0);
}

vec3 Film::pixel(int x, int y) const {
    const size_t i = size_t(y) * width_ + x;
    if (count_[i] == 0) return vec3(0.0f);
    const double inv = 1.0 / count_[i];
    auto mean = [&](int c) { return float(double(sum_[3 * i + c]) * 0x1p-48 * inv); };
    return vec3(mean(0), mean(1), mean(2));
}

void Film::add(const Film& other) {
    if (other.width_ != width_ || other.height_ != height_)
        fail("cannot add a ", other.width_, "x", other.height_, " film to a ", width_, "x", height_, " film");
    if (other.hasMomentSpace_ != hasMomentSpace_ || (hasMomentSpace_ && other.momentSpace_ != momentSpace_))
        fail("cannot add films whose second moments are in different colour spaces");
    for (size_t i = 0; i < sum_.size(); ++i) {
        sum_[i] += other.sum_[i];
        sumSq_[i] += other.sumSq_[i];
    }
    for (size_t i = 0; i < count_.size(); ++i) {
        if (count_[i] > UINT32_MAX - other.count_[i]) fail("film sample count overflows 2^32");
        count_[i] += other.count_[i];
    }
}

uint64_t Film::totalSamples() const {
    uint64_t s = 0;
    for (uint32_t c : count_) s += c;
    return s;
}

uint32_t Film::minSampleCount() const {
    uint32_t m = UINT32_MAX;
    for (uint32_t c : count_) m = std::min(m, c);
    return count_.empty() ? 0 : m;
}

std::vector<float> Film::meanImage() const {
    std::vector<float> img(3 * size_t(width_) * height_);
    for (int y = 0; y < height_; ++y)
        for (int x = 0; x < width_; ++x) {
            const vec3 p = pixel(x, y);
            const size_t i = 3 * (size_t(y) * width_ + x);
            img[i] = p.x;
            img[i + 1] = p.y;
            img[i + 2] = p.z;
        }
    return img;
}

std::vector<float> Film::secondMomentImage() const {
    std::vector<float> img(3 * size_t(width_) * height_, 0.0f);
    for (size_t i = 0; i < count_.size(); ++i)
        if (count_[i] > 0)
            for (int c = 0; c < 3; ++c) img[3 * i + c] = float(sumSq_[3 * i + c] / count_[i]);
    return img;
}

std::vector<float> Film::varianceOfMeanImage() const {
    std::vector<float> img(3 * size_t(width_) * height_, 0.0f);
    for (size_t i = 0; i < count_.size(); ++i) {
        const double n = count_[i];
        if (n < 2) continue;
        for (int c = 0; c < 3; ++c) {
            double mean = double(sum_[3 * i + c]) * 0x1p-48 / n;
            if (hasMomentSpace_) {  // E[(M v)_c] = Σ_k M_ck E[v_k] (glm is column-major: M[k][c])
                mean = 0.0;
                for (int k = 0; k < 3; ++k) mean += double(momentSpace_[k][c]) * (double(sum_[3 * i + k]) * 0x1p-48) / n;
            }
            const double var = std::max(0.0, (sumSq_[3 * i + c] - n * mean * mean) / (n - 1));
            img[3 * i + c] = float(var / n);
        }
    }
    return img;
}

// Checkpoint format 4 (host byte order; a checkpoint resumes on the machine that wrote it):
//   "IRISCKP4", uint64 header length, header (text; first line = settings key), int32 width,
//   int32 height, int128 sum[3wh] (fixed point, FixedSum), double sumSq[3wh], uint32 count[wh],
//   uint32 CRC-32 (zlib) of all bytes before it.
// Written atomically (core/io/atomic_file.h); reading checks size, checksum, header and film size
// before touching the film, so a truncated, corrupted or foreign file is refused, never resumed.
// (Version 3 was two different layouts on two branches: doubles with a CRC, or int128 without.)
namespace {

constexpr char kMagic[8] = {'I', 'R', 'I', 'S', 'C', 'K', 'P', '4'};
constexpr char kMagicPrefix[7] = {'I', 'R', 'I', 'S', 'C', 'K', 'P'};
constexpr uint64_t kMaxHeader = 1u << 20;
constexpr size_t kFixedPrefix = 8 + 8;  // magic, header length

template <typename T>
void append(std::string& out, const T* p, size_t n) {
    out.append(reinterpret_cast<const char*>(p), n * sizeof(T));
}

uint32_t crcOf(const char* p, size_t n) {
    uLong crc = crc32(0L, Z_NULL, 0);
    while (n > 0) {  // zlib's length is a uInt
        const uInt chunk = uInt(std::min<size_t>(n, 1u << 30));
        crc = crc32(crc, reinterpret_cast<const Bytef*>(p), chunk);
        p += chunk;
        n -= chunk;
    }
    return uint32_t(crc);
}

template <typename T>
void take(const std::string& in, size_t& pos, T* p, size_t n) {
    std::memcpy(p, in.data() + pos, n * sizeof(T));
    pos += n * sizeof(T);
}

std::string firstLine(const std::string& s) { return s.substr(0, s.find('\n')); }

/// Bytes of a checkpoint of a w×h film without its header.
uint64_t payloadBytes(uint64_t pixels) {
    return kFixedPrefix + 2 * sizeof(int32_t) + (3 * sizeof(Film::FixedSum) + 3 * sizeof(double) + sizeof(uint32_t)) * pixels + 4;
}

/// Checks magic and version of a whole file; returns its header; `pos` is set after it (at the
/// film size, whose 8 bytes are there).
std::string checkedHeader(const std::string& in, const std::string& path, size_t& pos) {
    if (in.size() < kFixedPrefix || std::memcmp(in.data(), kMagicPrefix, 7) != 0) fail(path, ": not an iris checkpoint (film state)");
    if (in[7] != kMagic[7])
        fail(path, ": checkpoint format version ", in[7], "; this iris reads version ", kMagic[7], " (render it again without --resume)");
    uint64_t hlen = 0;
    std::memcpy(&hlen, in.data() + 8, 8);
    if (hlen > kMaxHeader || in.size() < kFixedPrefix + hlen + 2 * sizeof(int32_t) + 4)
        fail(path, ": checkpoint is truncated or has the wrong size (", in.size(), " bytes)");
    pos = kFixedPrefix + hlen;
    return in.substr(kFixedPrefix, hlen);
}

/// A checkpoint of a w×h film with this header has exactly payloadBytes(w·h) + header bytes, and
/// the CRC-32 of everything before its last 4 bytes equals them (size first, so that a truncated
/// file is called truncated, not corrupted).
void checkSizeAndChecksum(const std::string& in, const std::string& path, int w, int h, size_t headerBytes) {
    const uint64_t expected = payloadBytes(uint64_t(w) * uint64_t(h)) + headerBytes;
    if (in.size() != expected)
        fail(path, ": checkpoint is truncated or has the wrong size (", in.size(), " bytes; a checkpoint of this ", w, "x", h,
             " film with this header has ", expected, ")");
    uint32_t stored = 0;
    std::memcpy(&stored, in.data() + in.size() - 4, 4);
    if (crcOf(in.data(), in.size() - 4) != stored) fail(path, ": checkpoint is corrupted (CRC-32 mismatch); render again without --resume");
}

}  // namespace

void Film::save(const std::string& path, const std::string& header) const {
    std::string out;
    out.reserve(payloadBytes(count_.size()) + header.size());
    const uint64_t hlen = header.size();
    append(out, kMagic, 8);
    append(out, &hlen, 1);
    append(out, header.data(), header.size());
    append(out, &width_, 1);
    append(out, &height_, 1);
    append(out, sum_.data(), sum_.size());
    append(out, sumSq_.data(), sumSq_.size());
    append(out, count_.data(), count_.size());
    const uint32_t crc = crcOf(out.data(), out.size());
    append(out, &crc, 1);
    writeFileAtomically(path, out);
}

void Film::takeBody(const std::string& in, size_t pos) {
    take(in, pos, sum_.data(), sum_.size());
    take(in, pos, sumSq_.data(), sumSq_.size());
    take(in, pos, count_.data(), count_.size());
}

void Film::load(const std::string& path, const std::string& key) {
    const std::string in = readInputFile(path, "checkpoint", payloadBytes(count_.size()) + kMaxHeader);
    size_t pos = 0;
    const std::string header = checkedHeader(in, path, pos);
    checkSizeAndChecksum(in, path, width_, height_, header.size());
    int32_t w = 0, h = 0;
    take(in, pos, &w, 1);
    take(in, pos, &h, 1);
    if (w != width_ || h != height_) fail(path, ": checkpoint film size differs");
    if (firstLine(header) != key) fail(path, ": checkpoint was made with a different scene or settings");
    takeBody(in, pos);  // every check passed: nothing below can fail, so an error leaves the film as it was
}

Film Film::read(const std::string& path, std::string* header) {
    const std::string in = readInputFile(path, "checkpoint", payloadBytes(uint64_t(1) << 28) + kMaxHeader);
    size_t pos = 0;
    *header = checkedHeader(in, path, pos);
    int32_t w = 0, h = 0;
    take(in, pos, &w, 1);
    take(in, pos, &h, 1);
    Film film(w, h);  // validates the size
    checkSizeAndChecksum(in, path, w, h, header->size());
    film.takeBody(in, pos);
    return film;
}

}  // namespace iris
