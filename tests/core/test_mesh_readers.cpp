// Mesh readers: OBJ, PLY (ASCII / binary LE / binary BE) and Mitsuba .serialized, including
// malformed, truncated and absurd inputs (each must throw iris::Error naming the file).
#include <gtest/gtest.h>

#include <bit>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <zlib.h>

#include "core/error.h"
#include "core/io/obj_reader.h"
#include "core/io/ply_reader.h"
#include "core/io/serialized_reader.h"
#include "core/source_tree.h"

namespace fs = std::filesystem;
using namespace iris;

namespace {

std::string tempPath(const std::string& name) {
    const fs::path dir = fs::temp_directory_path() / ("iris_mesh_tests_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    return (dir / name).string();
}

std::string writeFile(const std::string& name, const std::string& contents) {
    const std::string p = tempPath(name);
    std::ofstream(p, std::ios::binary) << contents;
    return p;
}

/// Expect an iris::Error whose message contains every fragment.
template <typename F>
void expectError(F&& f, std::initializer_list<std::string> fragments) {
    try {
        f();
        ADD_FAILURE() << "expected an iris::Error";
    } catch (const Error& e) {
        for (const auto& frag : fragments) EXPECT_NE(std::string(e.what()).find(frag), std::string::npos) << e.what() << "\n  missing: " << frag;
    }
}

template <typename T>
void put(std::string& s, T v, bool bigEndian = false) {
    char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    if (bigEndian) std::reverse(b, b + sizeof(T));
    s.append(b, sizeof(T));
}

}  // namespace

TEST(MeshReaders, ObjQuadFanNegativeIndicesAndDedup) {
    const std::string obj =
        "# a comment\n"
        "o thing\ng group\n"
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
        "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
        "vn 0 0 1\n"
        "usemtl whatever\ns off\n"
        "f 1/1/1 2/2/1 3/3/1 4/4/1\n"
        "f -4/-4/-1 -2/-2/-1 -1/-1/-1\n";  // repeats corners 1, 3, 4: no new vertices
    const TriangleMesh m = parseObj(obj, "quad.obj");
    ASSERT_EQ(m.positions.size(), 4u);
    ASSERT_EQ(m.indices.size(), 9u);
    EXPECT_EQ(std::vector<uint32_t>(m.indices.begin(), m.indices.begin() + 6), (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
    EXPECT_EQ(std::vector<uint32_t>(m.indices.begin() + 6, m.indices.end()), (std::vector<uint32_t>{0, 2, 3}));
    ASSERT_EQ(m.normals.size(), 4u);
    EXPECT_EQ(m.normals[2], vec3(0, 0, 1));
    ASSERT_EQ(m.uvs.size(), 4u);
    EXPECT_EQ(m.uvs[1], vec2(1, 1));  // v flipped (Mitsuba convention)
    EXPECT_EQ(m.uvs[2], vec2(1, 0));
}

TEST(MeshReaders, ObjSplitsVerticesWithDifferentAttributes) {
    // Same position, two different normals: two output vertices.
    const TriangleMesh m = parseObj("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nvn 0 0 -1\n"
                                    "f 1//1 2//1 3//1\nf 1//2 3//2 2//2\n", "split.obj");
    EXPECT_EQ(m.positions.size(), 6u);
    EXPECT_EQ(m.normals.size(), 6u);
    EXPECT_TRUE(m.uvs.empty());
    // A corner without a normal drops normals altogether (face normals are used).
    const TriangleMesh m2 = parseObj("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3\n", "mixed.obj");
    EXPECT_TRUE(m2.normals.empty());
    EXPECT_EQ(m2.positions.size(), 3u);
}

TEST(MeshReaders, ObjErrorsNameFileAndLine) {
    expectError([] { parseObj("v 0 0 0\nv 1 x 0\n", "bad.obj"); }, {"bad.obj:2:", "number"});
    expectError([] { parseObj("v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 4\n", "range.obj"); }, {"range.obj:5:", "out of range"});
    expectError([] { parseObj("v 0 0 0\nv 1 0 0\nf 1 2\n", "short.obj"); }, {"short.obj:3:", "at least 3"});
    expectError([] { parseObj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 0 2\n", "zero.obj"); }, {"zero.obj:4:", "out of range"});
    expectError([] { parseObj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/ 2 3\n", "slash.obj"); }, {"slash.obj:4:"});
    expectError([] { parseObj("v 0 0 0\n", "empty.obj"); }, {"empty.obj", "no faces"});
    expectError([] { readObj(tempPath("does_not_exist.obj")); }, {"does_not_exist.obj", "cannot open"});
    const std::string p = writeFile("ok.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    EXPECT_EQ(readObj(p).triangleCount(), 1u);
}

namespace {
std::string plyHeader(const std::string& format, int nv, int nf, const std::string& faceList) {
    return "ply\nformat " + format + " 1.0\ncomment test\nelement vertex " + std::to_string(nv) +
           "\nproperty float x\nproperty float y\nproperty float z\nproperty float nx\nproperty float ny\n"
           "property float nz\nproperty float u\nproperty float v\nelement face " + std::to_string(nf) +
           "\nproperty " + faceList + " vertex_indices\nelement extra 1\nproperty list uchar int stuff\nend_header\n";
}

std::string binaryQuadPly(bool bigEndian, bool ushortIndices) {
    std::string s = plyHeader(bigEndian ? "binary_big_endian" : "binary_little_endian", 4, 1,
                              ushortIndices ? "list uchar ushort" : "list int int");
    const float verts[4][8] = {{0, 0, 0, 0, 0, 1, 0, 0}, {1, 0, 0, 0, 0, 1, 1, 0}, {1, 1, 0, 0, 0, 1, 1, 1}, {0, 1, 0, 0, 0, 1, 0, 1}};
    for (const auto& v : verts)
        for (float x : v) put(s, x, bigEndian);
    if (ushortIndices) {
        put<uint8_t>(s, 4);
        for (uint16_t i : {0, 1, 2, 3}) put(s, i, bigEndian);
    } else {
        put<int32_t>(s, 4, bigEndian);
        for (int32_t i : {0, 1, 2, 3}) put(s, i, bigEndian);
    }
    put<uint8_t>(s, 2);  // the skipped "extra" element
    put<int32_t>(s, 7, bigEndian);
    put<int32_t>(s, 8, bigEndian);
    return s;
}

void expectQuad(const TriangleMesh& m) {
    ASSERT_EQ(m.positions.size(), 4u);
    EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
    EXPECT_EQ(m.positions[2], vec3(1, 1, 0));
    ASSERT_EQ(m.normals.size(), 4u);
    EXPECT_EQ(m.normals[3], vec3(0, 0, 1));
    ASSERT_EQ(m.uvs.size(), 4u);
    EXPECT_EQ(m.uvs[1], vec2(1, 0));
}
}  // namespace

TEST(MeshReaders, PlyAsciiAndBinary) {
    const std::string ascii = plyHeader("ascii", 4, 1, "list uchar int") +
                              "0 0 0 0 0 1 0 0\n1 0 0 0 0 1 1 0\n1 1 0 0 0 1 1 1\n0 1 0 0 0 1 0 1\n4 0 1 2 3\n2 7 8\n";
    expectQuad(parsePly(ascii, "a.ply"));
    expectQuad(parsePly(binaryQuadPly(false, false), "le.ply"));
    expectQuad(parsePly(binaryQuadPly(true, false), "be.ply"));
    expectQuad(parsePly(binaryQuadPly(false, true), "le16.ply"));
    expectQuad(parsePly(binaryQuadPly(true, true), "be16.ply"));
    expectQuad(readPly(writeFile("quad.ply", binaryQuadPly(false, false))));
    // s t texture names and vertex_index
    const std::string st = "ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\nproperty double z\n"
                           "property float s\nproperty float t\nelement face 1\nproperty list uchar uint vertex_index\nend_header\n"
                           "0 0 0 0 0\n1 0 0 0.5 0\n0 1 0 0 0.25\n3 0 1 2\n";
    const TriangleMesh m = parsePly(st, "st.ply");
    ASSERT_EQ(m.uvs.size(), 3u);
    EXPECT_EQ(m.uvs[2], vec2(0, 0.25f));
    EXPECT_TRUE(m.normals.empty());
}

TEST(MeshReaders, PlyErrors) {
    expectError([] { parsePly("plx\n", "magic.ply"); }, {"magic.ply:1:", "PLY"});
    expectError([] { parsePly("ply\nformat ascii 1.0\nelement vertex 3\nproperty floaty x\nend_header\n", "type.ply"); },
                {"type.ply:4:", "floaty"});
    expectError([] { parsePly("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n", "noend.ply"); }, {"noend.ply", "end_header"});
    // Absurd count: refused before allocating.
    expectError([] { parsePly(plyHeader("binary_little_endian", 2000000000, 1, "list uchar int"), "huge.ply"); },
                {"huge.ply", "exceeds"});
    // Truncated binary body.
    std::string b = binaryQuadPly(false, false);
    b.resize(b.size() - 3);
    expectError([&] { parsePly(b, "trunc.ply"); }, {"trunc.ply", "end of file"});
    // ASCII: bad number reports its line.
    const std::string ascii = plyHeader("ascii", 4, 1, "list uchar int") +
                              "0 0 0 0 0 1 0 0\n1 0 0 0 0 1 1 0\n1 1 0 zz 0 1 1 1\n0 1 0 0 0 1 0 1\n4 0 1 2 3\n2 7 8\n";
    expectError([&] { parsePly(ascii, "num.ply"); }, {"num.ply:20:", "number"});
    // Index out of range.
    const std::string range = plyHeader("ascii", 4, 1, "list uchar int") +
                              "0 0 0 0 0 1 0 0\n1 0 0 0 0 1 1 0\n1 1 0 0 0 1 1 1\n0 1 0 0 0 1 0 1\n4 0 1 2 9\n2 7 8\n";
    expectError([&] { parsePly(range, "range.ply"); }, {"range.ply", "out of range"});
    expectError([] { readPly(tempPath("missing.ply")); }, {"missing.ply", "cannot open"});
    // An element without properties stores nothing, whatever its count (no endless loop).
    const std::string empty = "ply\nformat ascii 1.0\nelement junk 18446744073709551615\nelement vertex 3\nproperty float x\n"
                              "property float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                              "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    EXPECT_EQ(parsePly(empty, "junk.ply").triangleCount(), 1u);
}

namespace {
/// Write a .serialized file with the given shapes (each a triangle list), format v3 or v4.
std::string serializedFile(int version, bool dbl, bool normals, bool uvs, int shapes) {
    std::string file;
    std::vector<uint64_t> offsets;
    for (int s = 0; s < shapes; ++s) {
        offsets.push_back(file.size());
        std::string raw;
        uint32_t flags = (normals ? 1u : 0u) | (uvs ? 2u : 0u) | (dbl ? 0x2000u : 0x1000u);
        put(raw, flags);
        if (version == 4) raw += "shape" + std::to_string(s) + '\0';
        put<uint64_t>(raw, 3);
        put<uint64_t>(raw, 1);
        const float p[3][3] = {{0, 0, float(s)}, {1, 0, float(s)}, {0, 1, float(s)}};
        auto putF = [&](float x) { dbl ? put<double>(raw, x) : put<float>(raw, x); };
        for (const auto& v : p)
            for (float x : v) putF(x);
        if (normals)
            for (int i = 0; i < 3; ++i) { putF(0); putF(0); putF(1); }
        if (uvs)
            for (int i = 0; i < 3; ++i) { putF(0.25f * i); putF(0.5f); }
        for (uint32_t i : {0u, 1u, 2u}) put(raw, i);
        uLongf len = compressBound(uLong(raw.size()));
        std::string z(len, '\0');
        compress(reinterpret_cast<Bytef*>(z.data()), &len, reinterpret_cast<const Bytef*>(raw.data()), uLong(raw.size()));
        z.resize(len);
        put<uint16_t>(file, 0x041C);
        put<uint16_t>(file, uint16_t(version));
        file += z;
    }
    for (uint64_t o : offsets) version == 4 ? put<uint64_t>(file, o) : put<uint32_t>(file, uint32_t(o));
    put<uint32_t>(file, uint32_t(shapes));
    return file;
}
}  // namespace

TEST(MeshReaders, SerializedWrittenFiles) {
    for (int version : {3, 4})
        for (bool dbl : {false, true}) {
            const std::string p = writeFile("s" + std::to_string(version) + (dbl ? "d" : "f") + ".serialized",
                                            serializedFile(version, dbl, true, true, 3));
            EXPECT_EQ(serializedShapeCount(p), 3);
            const SerializedMesh s = readSerialized(p, 2);
            ASSERT_EQ(s.mesh.positions.size(), 3u);
            EXPECT_EQ(s.mesh.positions[1], vec3(1, 0, 2));
            ASSERT_EQ(s.mesh.normals.size(), 3u);
            EXPECT_EQ(s.mesh.normals[0], vec3(0, 0, 1));
            ASSERT_EQ(s.mesh.uvs.size(), 3u);
            EXPECT_EQ(s.mesh.uvs[2], vec2(0.5f, 0.5f));
            EXPECT_EQ(s.mesh.indices, (std::vector<uint32_t>{0, 1, 2}));
            if (version == 4) EXPECT_NE(s.mesh.name.find("shape2"), std::string::npos);
            expectError([&] { readSerialized(p, 3); }, {p, "shape_index 3", "3 shapes"});
        }
}

TEST(MeshReaders, SerializedCorruptInput) {
    const std::string good = serializedFile(4, false, false, false, 2);
    // Truncated: cut into the first shape's stream but keep a valid dictionary shape.
    std::string cut = good.substr(0, 20);
    expectError([&] { readSerialized(writeFile("cut.serialized", cut), 0); }, {"cut.serialized"});
    std::string badMagic = good;
    badMagic[0] = 0x55;
    expectError([&] { readSerialized(writeFile("magic.serialized", badMagic), 0); }, {"magic.serialized", "magic"});
    // Absurd counts inside a well-formed compressed stream.
    std::string raw;
    put<uint32_t>(raw, 0x1000);
    raw += std::string("x") + '\0';
    put<uint64_t>(raw, 1ull << 40);
    put<uint64_t>(raw, 1ull << 40);
    uLongf len = compressBound(uLong(raw.size()));
    std::string z(len, '\0');
    compress(reinterpret_cast<Bytef*>(z.data()), &len, reinterpret_cast<const Bytef*>(raw.data()), uLong(raw.size()));
    z.resize(len);
    std::string absurd;
    put<uint16_t>(absurd, 0x041C);
    put<uint16_t>(absurd, 4);
    absurd += z;
    put<uint64_t>(absurd, 0);
    put<uint32_t>(absurd, 1);
    expectError([&] { readSerialized(writeFile("absurd.serialized", absurd), 0); }, {"absurd.serialized", "absurd"});
    // Plausible counts but a stream that ends early: "truncated", without allocating the claim.
    std::string shortRaw;
    put<uint32_t>(shortRaw, 0x1000);
    shortRaw += std::string("y") + '\0';
    put<uint64_t>(shortRaw, 1000);
    put<uint64_t>(shortRaw, 1000);
    for (int i = 0; i < 30; ++i) put<float>(shortRaw, float(i));
    len = compressBound(uLong(shortRaw.size()));
    z.assign(len, '\0');
    compress(reinterpret_cast<Bytef*>(z.data()), &len, reinterpret_cast<const Bytef*>(shortRaw.data()), uLong(shortRaw.size()));
    z.resize(len);
    std::string shortFile;
    put<uint16_t>(shortFile, 0x041C);
    put<uint16_t>(shortFile, 4);
    shortFile += z;
    for (int i = 0; i < 200; ++i) shortFile += char(0);  // padding after the stream
    put<uint64_t>(shortFile, 0);
    put<uint32_t>(shortFile, 1);
    expectError([&] { readSerialized(writeFile("short.serialized", shortFile), 0); }, {"short.serialized", "truncated"});
    // Corrupt compressed bytes.
    std::string garbled = good;
    for (size_t i = 6; i < 14; ++i) garbled[i] = char(0xA5);
    expectError([&] { readSerialized(writeFile("garbled.serialized", garbled), 0); }, {"garbled.serialized"});
    // Dictionary claiming too many shapes.
    std::string dict = good;
    const uint32_t many = 0x7fffffff;
    std::memcpy(dict.data() + dict.size() - 4, &many, 4);
    expectError([&] { readSerialized(writeFile("dict.serialized", dict), 0); }, {"dict.serialized", "dictionary"});
}

TEST(MeshReaders, SerializedMatpreview) {
    const std::string path = sourcePath("../shared/data/scenes/matpreview/matpreview.serialized");
    if (!fs::exists(path)) GTEST_SKIP() << "shared data not available";
    ASSERT_EQ(serializedShapeCount(path), 3);
    size_t total = 0;
    for (int i = 0; i < 3; ++i) {
        const SerializedMesh s = readSerialized(path, i);
        EXPECT_GT(s.mesh.triangleCount(), 0u);
        EXPECT_FALSE(s.mesh.normals.empty());
        for (const vec3& n : s.mesh.normals) ASSERT_NEAR(glm::length(n), 1.0f, 1e-3f);
        total += s.mesh.triangleCount();
    }
    EXPECT_GT(total, 1000u);
}
