// The `mesh_attribute` texture (materials/textures/mesh_attribute.cpp): lookups interpolate vertex
// attributes with the hit's barycentrics and keep face attributes constant; a diffuse quad coloured
// by its PLY vertex colours under a uniform environment renders its albedo (both in RGB and in
// spectral mode), the interpolated colour at the centre of a quad of four colours; an emitting quad
// shines its vertex colours (light samples and hits agree); and a mesh_attribute that its shape
// cannot serve is refused when the scene loads, naming file:line.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/mesh.h"
#include "core/registry.h"
#include "core/rng.h"
#include "materials/material.h"
#include "render/lights/light.h"
#include "materials/textures/texture.h"
#include "spectral/color_space.h"
#include "tests/support/error_of.h"
#include "tests/support/image_mean.h"

namespace fs = std::filesystem;

namespace iris {
namespace {

const SampledWavelengths kRGB = SampledWavelengths::rgb(defaultChannelWavelengths());
const SourceLocation kLoc{"<test>", 1};

fs::path tempDir() {
    const fs::path d = fs::temp_directory_path() / ("iris_mesh_attribute_tests_" + std::to_string(::getpid()));
    fs::create_directories(d);
    return d;
}

/// IEC 61966-2-1 decoding of an 8-bit code (the independent reference for uchar colours).
double decode(int code) {
    const double v = code / 255.0;
    return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
}

/// The quad [−1, 1]² at z = 0 facing +z, vertices (−1,−1), (1,−1), (1,1), (−1,1), as one polygon
/// (fanned into (0,1,2), (0,2,3)), with float vertex colours `c` and an uchar face colour `face`.
std::string writeQuad(const std::string& name, const vec3 c[4], const int face[3]) {
    const fs::path p = tempDir() / name;
    std::ofstream f(p);
    f << "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
         "property float r\nproperty float g\nproperty float b\nproperty float quality\n"
         "element face 1\nproperty list uchar int vertex_indices\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n"
         "end_header\n";
    const char* xy[4] = {"-1 -1", "1 -1", "1 1", "-1 1"};
    for (int v = 0; v < 4; ++v) f << xy[v] << " 0 " << c[v].x << " " << c[v].y << " " << c[v].z << " " << 0.1 * (v + 1) << "\n";
    f << "4 0 1 2 3 " << face[0] << " " << face[1] << " " << face[2] << "\n";
    return p.string();
}

/// A 4 × 4 image of the middle of the quad (field of view `fov` degrees from z = 2) with `bsdf`,
/// lit by a uniform environment of radiance RGB (1, 1, 1).
std::string quadScene(const std::string& ply, const std::string& bsdf, float fov) {
    return "<scene version=\"3.0.0\">\n<integrator type=\"direct\"/>\n"
           "<sensor type=\"perspective\"><float name=\"fov\" value=\"" + std::to_string(fov) + "\"/>\n"
           "<transform name=\"to_world\"><lookat origin=\"0, 0, 2\" target=\"0, 0, 0\" up=\"0, 1, 0\"/></transform>\n"
           "<film type=\"hdrfilm\"><integer name=\"width\" value=\"4\"/><integer name=\"height\" value=\"4\"/></film></sensor>\n"
           "<emitter type=\"constant\"><rgb name=\"radiance\" value=\"1\"/></emitter>\n"
           "<shape type=\"ply\"><string name=\"filename\" value=\"" + ply + "\"/>\n"
           + bsdf + "</shape>\n</scene>\n";
}

std::string bsdf(const std::string& type, const std::string& texture) {
    return "<bsdf type=\"" + type + "\">\n" + texture + "\n</bsdf>";
}

std::string attributeTexture(const std::string& param, const std::string& attr, const std::string& extra = "") {
    return "<texture type=\"mesh_attribute\" name=\"" + param + "\"><string name=\"name\" value=\"" + attr + "\"/>" + extra + "</texture>";
}

/// The image's mean linear Rec.709 colour (spectral films hold XYZ) and the largest standard error.
vec3 renderMean(const std::string& xml, bool rgb, double* stderrOut) {
    const Film film = test::renderXml(xml, 4, 4, 1024, 7, rgb);
    dvec3 sum(0.0), sum2(0.0);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) {
            const dvec3 px(film.pixel(x, y));
            const dvec3 c = rgb ? px : xyzToLinearRec709(px);
            sum += c;
            sum2 += c * c;
        }
    const dvec3 mean = sum / 16.0;
    const dvec3 var = glm::max(sum2 / 16.0 - mean * mean, dvec3(0.0)) / 15.0;
    *stderrOut = std::sqrt(std::max({var.x, var.y, var.z}));
    return vec3(mean);
}

void expectColour(const vec3& got, const dvec3& want, double tol, const char* what) {
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], want[c], tol) << what << " channel " << c;
}

/// The 1-based line of the first `needle` in `text`.
int lineOf(const std::string& text, const std::string& needle) {
    const size_t at = text.find(needle);
    return 1 + int(std::count(text.begin(), text.begin() + std::ptrdiff_t(at), '\n'));
}

/// A mesh of two triangles (0,1,2), (0,2,3) with a 3-channel vertex attribute, a 1-channel vertex
/// attribute and a 1-channel face attribute.
TriangleMesh attributeMesh() {
    TriangleMesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    m.indices = {0, 1, 2, 0, 2, 3};
    m.attributes.push_back({"vertex_color", 3, {0.9f, 0.1f, 0.2f, 0.1f, 0.8f, 0.3f, 0.2f, 0.3f, 0.7f, 0.5f, 0.5f, 0.5f}});
    m.attributes.push_back({"vertex_height", 1, {1.0f, 2.0f, 4.0f, 8.0f}});
    m.attributes.push_back({"face_id", 1, {10.0f, 20.0f}});
    m.validate();
    return m;
}

Properties textureProps(const std::string& attr, float scale) {
    Properties p("texture", "mesh_attribute", kLoc);
    p.set("name", attr, kLoc);
    p.set("scale", scale, kLoc);
    return p;
}

}  // namespace

TEST(MeshAttribute, LookupsInterpolateVertexValuesAndKeepFaceValues) {
    const TriangleMesh m = attributeMesh();
    TextureQuery q;
    q.mesh = &m;
    q.triangle = 1;               // corners 0, 2, 3
    q.bary = vec2(0.25f, 0.5f);   // weights 0.25, 0.25, 0.5
    const auto color = SpectrumTextureRegistry::instance().create(textureProps("vertex_color", 2.0f), SpectrumKind::Reflectance);
    const SampledSpectrum s = color->eval(q, kRGB);
    const float* v = m.attributes[0].values.data();
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(s[c], 2.0f * (0.25f * v[c] + 0.25f * v[6 + c] + 0.5f * v[9 + c]), 1e-6f) << c;
    const auto height = FloatTextureRegistry::instance().create(textureProps("vertex_height", 1.0f));
    EXPECT_FLOAT_EQ(height->eval(q), 0.25f * 1.0f + 0.25f * 4.0f + 0.5f * 8.0f);
    const auto id = FloatTextureRegistry::instance().create(textureProps("face_id", 0.5f));
    EXPECT_EQ(id->eval(q), 10.0f);
    q.bary = vec2(0.9f, 0.05f);
    EXPECT_EQ(id->eval(q), 10.0f);  // constant over the triangle
    q.triangle = 0;
    EXPECT_EQ(id->eval(q), 5.0f);
    // A 1-channel attribute as a spectrum is grey; without a mesh (analytic shapes, code) it is 0.
    const auto grey = SpectrumTextureRegistry::instance().create(textureProps("vertex_height", 1.0f), SpectrumKind::Reflectance);
    q.bary = vec2(0.0f, 1.0f);  // vertex 2 of triangle 0
    EXPECT_EQ(grey->eval(q, kRGB)[1], 4.0f);
    EXPECT_EQ(grey->eval(TextureQuery{}, kRGB)[1], 0.0f);
}

TEST(MeshAttribute, AQuadOfOneVertexColourRendersThatAlbedo) {
    // uchar colours are sRGB-decoded (as Mitsuba 3's PLY loader does); written here as float
    // vertex colours of the decoded values, and as the uchar face colour.
    const int code[3] = {200, 120, 40};
    const dvec3 want(decode(code[0]), decode(code[1]), decode(code[2]));
    const vec3 lin(want);
    const vec3 same[4] = {lin, lin, lin, lin};
    const std::string ply = writeQuad("uniform.ply", same, code);
    for (const bool rgb : {true, false}) {
        for (const char* attr : {"vertex_color", "face_color"}) {
            double se = 0;
            const vec3 got = renderMean(quadScene(ply, bsdf("diffuse", attributeTexture("reflectance", attr)), 20.0f), rgb, &se);
            expectColour(got, want, 5 * se + (rgb ? 1e-4 : 2e-3), attr);
        }
    }
}

TEST(MeshAttribute, AQuadOfFourVertexColoursShowsTheInterpolatedColourAtItsCentre) {
    const vec3 c[4] = {{0.9f, 0.1f, 0.1f}, {0.1f, 0.9f, 0.1f}, {0.1f, 0.1f, 0.9f}, {0.5f, 0.5f, 0.5f}};
    const int face[3] = {0, 0, 0};
    const std::string ply = writeQuad("four.ply", c, face);
    // The quad is fanned into (0,1,2), (0,2,3): its centre lies on the diagonal 0–2, where the
    // interpolated colour is (c0 + c2)/2; a view 0.017 units wide averages it within ~0.002.
    const dvec3 want = 0.5 * (dvec3(c[0]) + dvec3(c[2]));
    const dvec3 otherDiagonal = 0.5 * (dvec3(c[1]) + dvec3(c[3]));
    for (const bool rgb : {true, false}) {
        double se = 0;
        const vec3 got = renderMean(quadScene(ply, bsdf("diffuse", attributeTexture("reflectance", "vertex_color")), 0.5f), rgb, &se);
        const double tol = 5 * se + 5e-3;
        expectColour(got, want, tol, rgb ? "rgb" : "spectral");
        EXPECT_GT(std::abs(got.y - otherDiagonal.y), 10 * tol);  // the test can tell the diagonals apart
    }
    // scale multiplies the value.
    double se = 0;
    const vec3 half = renderMean(quadScene(ply, bsdf("diffuse", attributeTexture("reflectance", "vertex_color", "<float name=\"scale\" value=\"0.5\"/>")), 0.5f), true, &se);
    expectColour(half, 0.5 * want, 5 * se + 5e-3, "scale 0.5");
}

TEST(MeshAttribute, WhatAShapeCannotServeIsAnErrorAtLoad) {
    const vec3 grey(0.5f);
    const vec3 c[4] = {grey, grey, grey, grey};
    const int face[3] = {1, 2, 3};
    const std::string ply = writeQuad("errors.ply", c, face);
    auto loadError = [](const std::string& xml) { return test::errorOf([&] { loadSceneFromString(xml, "."); }); };
    auto expectAt = [](const std::string& message, const std::string& xml, std::initializer_list<std::string> parts) {
        const std::string where = "<string>:" + std::to_string(lineOf(xml, "<texture")) + ":";
        EXPECT_NE(message.find(where), std::string::npos) << message << "\n  expected " << where;
        for (const std::string& p : parts) EXPECT_NE(message.find(p), std::string::npos) << message << "\n  missing " << p;
    };
    // A missing attribute (the spelling differs): named with the ones the mesh has.
    const std::string missing = quadScene(ply, bsdf("diffuse", attributeTexture("reflectance", "vertex_colour")), 20.0f);
    expectAt(loadError(missing), missing, {"vertex_colour", "no such attribute", "vertex_color", "face_color", "vertex_quality"});
    // A 3-channel attribute read as a float (roughness).
    const std::string asFloat = quadScene(ply, bsdf("roughconductor", attributeTexture("alpha", "vertex_color")), 20.0f);
    expectAt(loadError(asFloat), asFloat, {"vertex_color", "3 channels", "float"});
    // ... while a 1-channel one is fine.
    EXPECT_EQ(loadError(quadScene(ply, bsdf("roughconductor", attributeTexture("alpha", "vertex_quality")), 20.0f)), "");
    // An analytic shape has no attributes.
    const std::string sphere = "<scene version=\"3.0.0\">\n<shape type=\"sphere\">\n<bsdf type=\"diffuse\">\n" +
                               attributeTexture("reflectance", "vertex_color") + "\n</bsdf></shape></scene>";
    expectAt(loadError(sphere), sphere, {"vertex_color", "sphere", "no mesh attributes"});
    // Names must say vertex_ or face_ (Mitsuba's rule).
    const std::string badName = quadScene(ply, bsdf("diffuse", attributeTexture("reflectance", "color")), 20.0f);
    EXPECT_NE(loadError(badName).find("must start with \"vertex_\" or \"face_\""), std::string::npos) << loadError(badName);
    // An area emitter on a sphere, and a scene-level emitter (a spot's slide), have no attributes.
    const std::string sphereLamp = "<scene version=\"3.0.0\">\n<shape type=\"sphere\">\n<emitter type=\"area\">\n" +
                                   attributeTexture("radiance", "vertex_color") + "\n</emitter></shape></scene>";
    expectAt(loadError(sphereLamp), sphereLamp, {"vertex_color", "sphere", "no mesh attributes"});
    const std::string spot = "<scene version=\"3.0.0\">\n<emitter type=\"spot\">\n" + attributeTexture("texture", "vertex_color") +
                             "\n</emitter></scene>";
    expectAt(loadError(spot), spot, {"vertex_color", "spot emitter", "no mesh attributes"});
}

TEST(MeshAttribute, AnEmitterColouredByItsVerticesShinesTheirInterpolatedColour) {
    const vec3 c[4] = {{2.0f, 0.2f, 0.4f}, {0.3f, 1.5f, 0.1f}, {0.4f, 0.6f, 3.0f}, {1.0f, 1.0f, 1.0f}};
    const int face[3] = {0, 0, 0};
    const std::string ply = writeQuad("lamp.ply", c, face);
    const std::string lamp = "<shape type=\"ply\"><string name=\"filename\" value=\"" + ply + "\"/>\n<emitter type=\"area\">" +
                             attributeTexture("radiance", "vertex_color") + "</emitter></shape>\n";
    // A light sample and the ray towards it see the same radiance: the sample's barycentrics are
    // those the hit gets (render/lights/area_light.cpp), and the colour varies over the quad.
    Scene scene(loadSceneFromString("<scene version=\"3.0.0\">" + lamp + "</scene>", "."));
    ASSERT_EQ(scene.lights().size(), 1u);
    Pcg32 rng(3, 1);
    int checked = 0;
    float lowest = 1e9f, highest = 0.0f;
    for (int i = 0; i < 200; ++i) {
        const vec3 p(0.1f, -0.2f, 3.0f);
        const auto ls = scene.lights()[0]->sampleLi(p, vec2(rng.uniform(), rng.uniform()), kRGB);
        ASSERT_TRUE(ls.has_value());
        const auto hit = scene.intersect(Ray(p, ls->wi));
        ASSERT_TRUE(hit.has_value());
        const SampledSpectrum le = hit->areaLight->Le(textureQueryAt(*hit), hit->ng, hit->wo, kRGB);
        for (int k = 0; k < 3; ++k) EXPECT_NEAR(le[k], ls->L[k], 1e-4f * (1 + le[k]));
        lowest = std::min(lowest, le[0]);
        highest = std::max(highest, le[0]);
        ++checked;
    }
    EXPECT_EQ(checked, 200);
    EXPECT_GT(highest - lowest, 0.5f);  // the samples spread over different colours
    // Seen directly, the middle of the quad shows (c0 + c2)/2 (see the reflectance test above).
    const std::string xml = "<scene version=\"3.0.0\">\n<integrator type=\"direct\"/>\n"
                            "<sensor type=\"perspective\"><float name=\"fov\" value=\"0.5\"/>\n"
                            "<transform name=\"to_world\"><lookat origin=\"0, 0, 2\" target=\"0, 0, 0\" up=\"0, 1, 0\"/></transform>\n"
                            "<film type=\"hdrfilm\"><integer name=\"width\" value=\"4\"/><integer name=\"height\" value=\"4\"/></film></sensor>\n" +
                            lamp + "</scene>\n";
    const dvec3 want = 0.5 * (dvec3(c[0]) + dvec3(c[2]));
    for (const bool rgb : {true, false}) {
        double se = 0;
        expectColour(renderMean(xml, rgb, &se), want, 5 * se + 0.02, rgb ? "rgb" : "spectral");
    }
}

}  // namespace iris
