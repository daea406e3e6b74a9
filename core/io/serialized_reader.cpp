#include "core/io/serialized_reader.h"

#include <cstring>

#include <zlib.h>

#include "core/error.h"
#include "core/input_file.h"
#include "core/memory_budget.h"

namespace iris {
namespace {

static_assert(sizeof(vec3) == 3 * sizeof(float) && sizeof(vec2) == 2 * sizeof(float), "packed GLM vectors");

constexpr uint16_t kMagic = 0x041C;
constexpr uint32_t kHasNormals = 0x0001, kHasUVs = 0x0002, kHasColors = 0x0008, kFaceNormals = 0x0010,
                   kDouble = 0x2000;
// zlib's deflate cannot compress better than about 1032:1; anything claiming more is corrupt.
constexpr uint64_t kMaxZlibRatio = 1100;

std::string readAll(const std::string& path) { return readInputFile(path, "serialized mesh file"); }

template <typename T>
T readLE(const std::string& d, size_t at) {
    T v;
    std::memcpy(&v, d.data() + at, sizeof(T));  // the format and every supported host are little endian
    return v;
}

/// Offsets of every shape, from the dictionary at the end of the file.
struct Dictionary {
    std::vector<uint64_t> offsets;
    uint64_t end = 0;  // start of the dictionary = end of the last shape
    int version = 0;
};

Dictionary readDictionary(const std::string& d, const std::string& path) {
    if (d.size() < 8) fail(path, ": file too small to be a Mitsuba serialized mesh");
    if (readLE<uint16_t>(d, 0) != kMagic) fail(path, ": not a Mitsuba serialized mesh (bad magic number)");
    Dictionary dict;
    dict.version = readLE<uint16_t>(d, 2);
    if (dict.version != 3 && dict.version != 4)
        fail(path, ": unsupported serialized format version ", dict.version, " (supported: 3, 4)");
    const uint32_t count = readLE<uint32_t>(d, d.size() - 4);
    const uint64_t entry = dict.version == 4 ? 8 : 4;
    if (count == 0 || uint64_t(count) * entry + 4 > d.size()) fail(path, ": corrupt shape dictionary (", count, " shapes)");
    dict.end = d.size() - 4 - uint64_t(count) * entry;
    for (uint32_t i = 0; i < count; ++i) {
        const size_t at = size_t(dict.end + i * entry);
        const uint64_t off = entry == 8 ? readLE<uint64_t>(d, at) : readLE<uint32_t>(d, at);
        // Each shape holds at least its 4-byte header; no "off + 4", which wraps for offsets
        // near 2^64 (found by fuzz_serialized, tests/fuzz/corpus/serialized/crash-offset-wraps).
        const bool pastEnd = off > dict.end || dict.end - off < 4;
        const bool overlaps = i > 0 && (off < dict.offsets.back() || off - dict.offsets.back() < 4);
        if (pastEnd || overlaps)
            fail(path, ": corrupt shape dictionary (offset of shape ", i, ")");
        dict.offsets.push_back(off);
    }
    return dict;
}

/// Streaming zlib inflater over one shape's compressed bytes.
class Inflater {
public:
    Inflater(const char* data, size_t size, std::string path) : path_(std::move(path)) {
        std::memset(&z_, 0, sizeof(z_));
        if (inflateInit(&z_) != Z_OK) fail(path_, ": zlib initialisation failed");
        z_.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data));
        z_.avail_in = uInt(size);
    }
    ~Inflater() { inflateEnd(&z_); }
    Inflater(const Inflater&) = delete;
    Inflater& operator=(const Inflater&) = delete;

    void read(void* dst, size_t n) {
        z_.next_out = static_cast<Bytef*>(dst);
        while (n > 0) {
            const uInt chunk = uInt(std::min<size_t>(n, 1u << 30));
            z_.avail_out = chunk;
            z_.next_out = static_cast<Bytef*>(dst);
            const int r = inflate(&z_, Z_SYNC_FLUSH);
            const size_t got = chunk - z_.avail_out;
            dst = static_cast<char*>(dst) + got;
            n -= got;
            if (n == 0) break;
            if (r == Z_STREAM_END || (r == Z_BUF_ERROR && z_.avail_in == 0))
                fail(path_, ": truncated serialized mesh data");
            if (r != Z_OK) fail(path_, ": corrupt compressed mesh data (zlib: ", z_.msg ? z_.msg : "error", ")");
        }
    }
    template <typename T>
    T get() {
        T v;
        read(&v, sizeof(T));
        return v;
    }

private:
    z_stream z_;
    std::string path_;
};

/// Read `count` items in bounded chunks, so that memory grows only with data actually present
/// (a truncated stream fails before a huge claimed count is allocated).
template <typename T>
void readChunked(Inflater& in, std::vector<T>& out, uint64_t count) {
    constexpr uint64_t kChunk = uint64_t(1) << 20;
    out.clear();
    for (uint64_t done = 0; done < count;) {
        const uint64_t n = std::min(kChunk, count - done);
        out.resize(size_t(done + n));
        in.read(out.data() + done, size_t(n) * sizeof(T));
        done += n;
    }
}

template <typename Vec, int N>
void readVectors(Inflater& in, std::vector<Vec>& out, uint64_t count, bool dbl) {
    if (dbl) {
        std::vector<double> tmp;
        readChunked(in, tmp, count * N);
        out.resize(size_t(count));
        for (size_t i = 0; i < count; ++i)
            for (int k = 0; k < N; ++k) out[i][k] = float(tmp[i * N + size_t(k)]);
    } else {
        std::vector<float> tmp;
        readChunked(in, tmp, count * N);
        out.resize(size_t(count));
        std::memcpy(out.data(), tmp.data(), tmp.size() * sizeof(float));
    }
}

}  // namespace

int serializedShapeCount(const std::string& path) {
    const std::string d = readAll(path);
    return int(readDictionary(d, path).offsets.size());
}

SerializedMesh readSerialized(const std::string& path, int shapeIndex) {
    const std::string d = readAll(path);
    const Dictionary dict = readDictionary(d, path);
    if (shapeIndex < 0 || size_t(shapeIndex) >= dict.offsets.size())
        fail(path, ": shape_index ", shapeIndex, " out of range (the file has ", dict.offsets.size(), " shapes)");
    const uint64_t start = dict.offsets[size_t(shapeIndex)];
    const uint64_t stop = size_t(shapeIndex) + 1 < dict.offsets.size() ? dict.offsets[size_t(shapeIndex) + 1] : dict.end;
    if (readLE<uint16_t>(d, size_t(start)) != kMagic) fail(path, ": shape ", shapeIndex, ": bad magic number");
    const int version = readLE<uint16_t>(d, size_t(start) + 2);
    if (version != 3 && version != 4) fail(path, ": shape ", shapeIndex, ": unsupported version ", version);

    const std::string where = strCat(path, " (shape ", shapeIndex, ")");
    Inflater in(d.data() + start + 4, size_t(stop - start - 4), where);
    const uint32_t flags = in.get<uint32_t>();
    std::string name;
    if (version == 4) {
        for (char c; (c = in.get<char>()) != '\0';) {
            if (name.size() > 4096) fail(where, ": shape name too long");
            name += c;
        }
    }
    const uint64_t nv = in.get<uint64_t>(), nt = in.get<uint64_t>();
    const bool dbl = (flags & kDouble) != 0;
    const uint64_t scalar = dbl ? 8 : 4;
    const uint64_t maxBytes = (stop - start) * kMaxZlibRatio;
    // Check each count first so that the products below cannot overflow.
    if (nv > maxBytes || nt > maxBytes) fail(where, ": absurd vertex/triangle counts (", nv, ", ", nt, ")");
    const uint64_t perVertex = scalar * (3 + ((flags & kHasNormals) ? 3 : 0) + ((flags & kHasUVs) ? 2 : 0) +
                                         ((flags & kHasColors) ? 3 : 0));
    const bool wideIndices = nv > 0xFFFFFFFFull;
    const uint64_t needed = nv * perVertex + nt * 3 * (wideIndices ? 8 : 4);
    if (needed > maxBytes) fail(where, ": vertex/triangle counts (", nv, ", ", nt, ") exceed what the file can hold");
    if (nv == 0 || nt == 0) fail(where, ": empty mesh");
    if (wideIndices) fail(where, ": more than 2^32 vertices are not supported");
    // What the mesh will hold (float vectors, 32-bit indices; colours are read and dropped).
    const uint64_t held = nv * (sizeof(vec3) * (1 + ((flags & kHasNormals) ? 1 : 0) + ((flags & kHasColors) ? 1 : 0)) +
                                ((flags & kHasUVs) ? sizeof(vec2) : 0)) + nt * 3 * sizeof(uint32_t);
    chargeMemory(held, strCat(where, ": ", nv, " vertices and ", nt, " triangles"));

    SerializedMesh out;
    TriangleMesh& m = out.mesh;
    m.name = name.empty() ? where : strCat(path, " (shape ", shapeIndex, " '", name, "')");
    readVectors<vec3, 3>(in, m.positions, nv, dbl);
    if (flags & kHasNormals) readVectors<vec3, 3>(in, m.normals, nv, dbl);
    if (flags & kHasUVs) readVectors<vec2, 2>(in, m.uvs, nv, dbl);
    if (flags & kHasColors) {
        std::vector<vec3> colors;
        readVectors<vec3, 3>(in, colors, nv, dbl);
    }
    readChunked(in, m.indices, nt * 3);
    out.faceNormals = (flags & kFaceNormals) != 0;
    m.validate();
    return out;
}

}  // namespace iris
