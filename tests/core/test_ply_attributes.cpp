// PLY properties beyond positions, normals and uvs become mesh attributes (core/mesh.h
// MeshAttribute) named as Mitsuba 3's PLY loader names them (src/shapes/ply.h): vertex colours
// r g b / red green blue → `vertex_color` (integers divided by their maximum and decoded from sRGB,
// floats as stored), postfixed groups, other scalars as 1-channel attributes, face properties as
// `face_...` repeated on each triangle of a polygon. Vertex attributes interpolate with the
// barycentrics, face attributes are constant per triangle.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "core/error.h"
#include "core/io/ply_reader.h"

using namespace iris;

namespace {

/// IEC 61966-2-1 decoding, written out here as the independent reference.
float decode(int code) {
    const double v = code / 255.0;
    return float(v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4));
}

const char* kHeader =
    "element vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
    "property uchar red\nproperty uchar green\nproperty uchar blue\nproperty float quality\n"
    "element face 1\nproperty list uchar int vertex_indices\nproperty float weight\nend_header\n";
const int kColours[4][3] = {{255, 0, 128}, {10, 200, 30}, {64, 64, 64}, {0, 255, 255}};
const float kQuality[4] = {0.25f, -1.5f, 3.0f, 0.0f};

std::string asciiPly() {
    std::string s = std::string("ply\nformat ascii 1.0\n") + kHeader;
    const char* xyz[4] = {"0 0 0", "1 0 0", "1 1 0", "0 1 0"};
    for (int v = 0; v < 4; ++v)
        s += std::string(xyz[v]) + " " + std::to_string(kColours[v][0]) + " " + std::to_string(kColours[v][1]) + " " +
             std::to_string(kColours[v][2]) + " " + std::to_string(kQuality[v]) + "\n";
    return s + "4 0 1 2 3 0.75\n";
}

template <typename T>
void put(std::string& s, T v) {  // little endian (the test machine's order, checked below)
    char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    s.append(b, sizeof(T));
}

std::string binaryPly() {
    std::string s = std::string("ply\nformat binary_little_endian 1.0\n") + kHeader;
    const float xyz[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    for (int v = 0; v < 4; ++v) {
        for (float c : xyz[v]) put(s, c);
        for (int c : kColours[v]) put(s, uint8_t(c));
        put(s, kQuality[v]);
    }
    put(s, uint8_t(4));
    for (int i : {0, 1, 2, 3}) put(s, int32_t(i));
    put(s, 0.75f);
    return s;
}

void expectAttributes(const TriangleMesh& m) {
    ASSERT_EQ(m.triangleCount(), 2u);
    ASSERT_EQ(m.attributes.size(), 3u);
    const MeshAttribute* color = m.findAttribute("vertex_color");
    ASSERT_NE(color, nullptr);
    EXPECT_EQ(color->channels, 3);
    for (size_t v = 0; v < 4; ++v)
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(color->value(v, c), decode(kColours[v][c]), 1e-6f) << v << " " << c;
    EXPECT_FLOAT_EQ(color->value(0, 2), 0.2158605f);  // sRGB 128/255, the IEC value
    const MeshAttribute* quality = m.findAttribute("vertex_quality");
    ASSERT_NE(quality, nullptr);
    EXPECT_EQ(quality->channels, 1);
    for (size_t v = 0; v < 4; ++v) EXPECT_EQ(quality->value(v, 0), kQuality[v]);  // floats as stored
    const MeshAttribute* weight = m.findAttribute("face_weight");
    ASSERT_NE(weight, nullptr);
    EXPECT_TRUE(weight->perFace());
    ASSERT_EQ(weight->values.size(), 2u);  // the quad's value on both of its triangles
    EXPECT_EQ(weight->values[0], 0.75f);
    EXPECT_EQ(weight->values[1], 0.75f);
}

}  // namespace

TEST(PlyAttributes, VertexColoursAndScalarsAsciiAndBinary) {
    uint16_t one = 1;
    uint8_t first;
    std::memcpy(&first, &one, 1);
    ASSERT_EQ(first, 1) << "binaryPly writes the machine's byte order as little endian";
    expectAttributes(parsePly(asciiPly(), "a.ply"));
    expectAttributes(parsePly(binaryPly(), "le.ply"));
}

TEST(PlyAttributes, FloatColoursAreLinearAndMitsubaGroupsChannels) {
    const std::string ply =
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
        "property float r\nproperty float g\nproperty float b\nproperty float a\n"
        "property float albedo_r\nproperty float albedo_g\nproperty float albedo_b\n"
        "property float dir_x\nproperty float dir_y\nproperty float w_0\nproperty float w_1\nproperty float w_2\n"
        "element face 1\nproperty list uchar int vertex_indices\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n"
        "end_header\n"
        "0 0 0  0.5 0.25 2  0.9  1 2 3  4 5  6 7 8\n"
        "1 0 0  0 0 0  1  0 0 0  0 0  0 0 0\n"
        "0 1 0  0 0 0  1  0 0 0  0 0  0 0 0\n"
        "3 0 1 2 255 0 51\n";
    const TriangleMesh m = parsePly(ply, "groups.ply");
    const MeshAttribute* color = m.findAttribute("vertex_color");
    ASSERT_NE(color, nullptr);
    EXPECT_EQ(color->channels, 3);  // the alpha is dropped
    EXPECT_EQ(color->value(0, 0), 0.5f);
    EXPECT_EQ(color->value(0, 2), 2.0f);  // floats are not clamped nor decoded
    const MeshAttribute* albedo = m.findAttribute("vertex_albedo_color");  // Mitsuba: P_r P_g P_b → P_color
    ASSERT_NE(albedo, nullptr);
    EXPECT_EQ(albedo->channels, 3);
    EXPECT_EQ(albedo->value(0, 1), 2.0f);
    const MeshAttribute* dir = m.findAttribute("vertex_dir");
    ASSERT_NE(dir, nullptr);
    EXPECT_EQ(dir->channels, 2);
    const MeshAttribute* w = m.findAttribute("vertex_w");
    ASSERT_NE(w, nullptr);
    EXPECT_EQ(w->channels, 3);
    EXPECT_EQ(w->value(0, 2), 8.0f);
    const MeshAttribute* face = m.findAttribute("face_color");
    ASSERT_NE(face, nullptr);
    EXPECT_EQ(face->value(0, 0), 1.0f);
    EXPECT_EQ(face->value(0, 1), 0.0f);
    EXPECT_NEAR(face->value(0, 2), decode(51), 1e-6f);
    EXPECT_EQ(m.attributes.size(), 5u);
}

TEST(PlyAttributes, PlainMeshesHaveNone) {
    const std::string ply = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                            "property float nx\nproperty float ny\nproperty float nz\nproperty float u\nproperty float v\n"
                            "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
                            "0 0 0 0 0 1 0 0\n1 0 0 0 0 1 1 0\n0 1 0 0 0 1 0 1\n3 0 1 2\n";
    EXPECT_TRUE(parsePly(ply, "plain.ply").attributes.empty());
}

TEST(PlyAttributes, VertexValuesInterpolateFaceValuesStayConstant) {
    const TriangleMesh m = parsePly(asciiPly(), "a.ply");
    const MeshAttribute& q = *m.findAttribute("vertex_quality");
    const MeshAttribute& w = *m.findAttribute("face_weight");
    // Triangle 1 is (0, 2, 3) (the quad fanned from vertex 0); at barycentrics (b1, b2) = (0.2, 0.3)
    // the value is 0.5 q0 + 0.2 q2 + 0.3 q3.
    EXPECT_FLOAT_EQ(q.at(m, 1, vec2(0.2f, 0.3f), 0), 0.5f * kQuality[0] + 0.2f * kQuality[2] + 0.3f * kQuality[3]);
    EXPECT_FLOAT_EQ(q.at(m, 0, vec2(1.0f, 0.0f), 0), kQuality[1]);  // a corner gives its vertex's value
    for (const vec2 b : {vec2(0.0f), vec2(0.7f, 0.1f), vec2(0.0f, 1.0f)}) EXPECT_EQ(w.at(m, 1, b, 0), 0.75f);
    const MeshAttribute& c = *m.findAttribute("vertex_color");
    EXPECT_NEAR(c.at(m, 0, vec2(0.5f, 0.25f), 1), 0.25f * decode(0) + 0.5f * decode(200) + 0.25f * decode(64), 1e-6f);
}

TEST(PlyAttributes, MalformedAttributeDataIsAnError) {
    std::string truncated = binaryPly();
    truncated.resize(truncated.size() - 3);  // the face's weight cut short
    EXPECT_THROW(parsePly(truncated, "t.ply"), Error);
}
