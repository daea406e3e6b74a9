// Bitmap and checkerboard textures: lookups, filters, wrap modes, sRGB decoding, RGB vs spectral
// evaluation, registration in both texture registries and their use from scene files.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "core/io/image.h"
#include "render/loader/scene_loader.h"
#include "core/srgb_transfer.h"
#include "core/xml/xml_values.h"
#include "core/registry.h"
#include "materials/textures/bitmap.h"
#include "spectral/spectrum_factory.h"
#include "render/loader/scene_upgrade.h"

namespace fs = std::filesystem;
using namespace iris;

namespace {

fs::path texDir() {
    const fs::path d = fs::temp_directory_path() / ("iris_texture_tests_" + std::to_string(::getpid()));
    fs::create_directories(d);
    return d;
}

/// 2x2 RGB image: (0,0) red, (1,0) green, (0,1) blue, (1,1) white (row 0 = top).
Image quad() {
    Image img(2, 2, 3);
    const vec3 c[4] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}};
    for (int i = 0; i < 4; ++i)
        for (int k = 0; k < 3; ++k) img.at(i % 2, i / 2, k) = c[i][k];
    return img;
}

void expectVec(const vec3& a, const vec3& b, float tol = 1e-6f) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

const SourceLocation kLoc{"tex.xml", 1};

}  // namespace

TEST(SceneLoaderTextures, BitmapLookupsFiltersAndWraps) {
    const Bitmap b(quad());
    using F = Bitmap::Filter;
    using W = Bitmap::Wrap;
    expectVec(b.lookupRGB({0.25f, 0.25f}, F::Nearest, W::Repeat), {1, 0, 0});
    expectVec(b.lookupRGB({0.75f, 0.25f}, F::Nearest, W::Repeat), {0, 1, 0});
    expectVec(b.lookupRGB({0.25f, 0.75f}, F::Nearest, W::Repeat), {0, 0, 1});
    // Bilinear at a texel centre is that texel; at the image centre the mean of the four.
    expectVec(b.lookupRGB({0.75f, 0.75f}, F::Bilinear, W::Repeat), {1, 1, 1});
    expectVec(b.lookupRGB({0.5f, 0.5f}, F::Bilinear, W::Repeat), {0.5f, 0.5f, 0.5f});
    EXPECT_NEAR(b.lookupGrey({0.5f, 0.5f}, F::Bilinear, W::Repeat), 0.5f, 1e-6f);
    // Wrap modes at u = -0.25 (texel -1): repeat → texel 1, mirror → texel 0, clamp → texel 0.
    expectVec(b.lookupRGB({-0.25f, 0.25f}, F::Nearest, W::Repeat), {0, 1, 0});
    expectVec(b.lookupRGB({-0.25f, 0.25f}, F::Nearest, W::Mirror), {1, 0, 0});
    expectVec(b.lookupRGB({-0.25f, 0.25f}, F::Nearest, W::Clamp), {1, 0, 0});
    expectVec(b.lookupRGB({1.25f, 0.25f}, F::Nearest, W::Repeat), {1, 0, 0});
    expectVec(b.lookupRGB({1.25f, 0.25f}, F::Nearest, W::Mirror), {0, 1, 0});
    expectVec(b.lookupRGB({7.75f, 0.25f}, F::Nearest, W::Clamp), {0, 1, 0});
    // Bilinear across the repeat seam at u = 0: half texel 1, half texel 0.
    expectVec(b.lookupRGB({0.0f, 0.25f}, F::Bilinear, W::Repeat), {0.5f, 0.5f, 0});
    // Huge and non-finite coordinates stay in range.
    const vec3 h = b.lookupRGB({1e9f, std::nanf("")}, F::Bilinear, W::Mirror);
    EXPECT_TRUE(isFinite(h));
    EXPECT_THROW(Bitmap::parseWrap("tile", kLoc), Error);
    EXPECT_THROW(Bitmap::parseFilter("cubic", kLoc), Error);
    EXPECT_THROW(Bitmap{Image{}}, Error);
}

TEST(SceneLoaderTextures, BitmapFileSrgbDecoding) {
    Image img(2, 1, 3);
    for (int k = 0; k < 3; ++k) {
        img.at(0, 0, k) = 128.0f / 255.0f;
        img.at(1, 0, k) = 1.0f;
    }
    const std::string png = (texDir() / "grey.png").string();
    writeLDR(png, img);
    const auto decoded = Bitmap::load(png, false);
    const auto raw = Bitmap::load(png, true);
    EXPECT_NEAR(decoded->texel(0, 0), srgbToLinear(128.0f / 255.0f), 1e-5f);
    EXPECT_NEAR(raw->texel(0, 0), 128.0f / 255.0f, 1e-5f);
    EXPECT_NEAR(decoded->texel(1, 1), 1.0f, 1e-6f);
    EXPECT_EQ(Bitmap::load(png, false), decoded);  // shared while in use
    EXPECT_NE(Bitmap::loadUncached(png, false), decoded);
    // Float images are used as stored.
    Image f(1, 1, 3);
    f.at(0, 0, 0) = 0.25f;
    f.at(0, 0, 1) = 2.0f;
    f.at(0, 0, 2) = 0.5f;
    const std::string exr = (texDir() / "f.exr").string();
    writeEXR(exr, f);
    expectVec(Bitmap::load(exr, false)->texelRGB(0), {0.25f, 2.0f, 0.5f});
    // Broken files name the file.
    const std::string bad = (texDir() / "bad.png").string();
    std::ofstream(bad) << "not a png";
    try {
        Bitmap::load(bad, false);
        ADD_FAILURE();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("bad.png"), std::string::npos) << e.what();
    }
}

TEST(SceneLoaderTextures, BitmapTextureRGBAndSpectralModes) {
    const std::string exr = (texDir() / "quad.exr").string();
    writeEXR(exr, quad());
    Properties p("texture", "bitmap", kLoc);
    p.set("filename", exr, kLoc);
    p.set("filter_type", std::string("nearest"), kLoc);
    const SpectrumTexturePtr t = SpectrumTextureRegistry::instance().create(p, SpectrumKind::Reflectance);
    TextureQuery q;
    q.uv = {0.75f, 0.25f};  // green texel
    const SampledWavelengths rgb = SampledWavelengths::rgb(defaultChannelWavelengths());
    const SampledSpectrum s = t->eval(q, rgb);
    EXPECT_EQ(s[0], 0.0f);
    EXPECT_EQ(s[1], 1.0f);
    EXPECT_EQ(s[2], 0.0f);
    // Spectral mode: the texel's upsampled spectrum.
    const SampledWavelengths wl = SampledWavelengths::sampleVisible(0.3f, 8);
    const SampledSpectrum sp = t->eval(q, wl);
    const SampledSpectrum ref = makeRGBSpectrum(vec3(0, 1, 0), SpectrumKind::Reflectance)->sample(wl);
    for (int i = 0; i < wl.size(); ++i) EXPECT_NEAR(sp[i], ref[i], 1e-6f) << wl.lambda(i);
    // Bilinear spectral lookup interpolates the texels' spectra.
    Properties pb("texture", "bitmap", kLoc);
    pb.set("filename", exr, kLoc);
    pb.set("wrap_mode", std::string("clamp"), kLoc);
    const SpectrumTexturePtr tb = SpectrumTextureRegistry::instance().create(pb, SpectrumKind::Reflectance);
    q.uv = {0.5f, 0.25f};  // halfway between red and green
    const SampledSpectrum mix = tb->eval(q, wl);
    const SampledSpectrum red = makeRGBSpectrum(vec3(1, 0, 0), SpectrumKind::Reflectance)->sample(wl);
    for (int i = 0; i < wl.size(); ++i) EXPECT_NEAR(mix[i], 0.5f * (red[i] + ref[i]), 1e-5f);
    // Float texture: grey = channel mean.
    Properties pf("texture", "bitmap", kLoc);
    pf.set("filename", exr, kLoc);
    pf.set("to_uv", glm::translate(mat4(1.0f), vec3(0.5f, 0, 0)), kLoc);  // shifts red → green column
    const FloatTexturePtr f = FloatTextureRegistry::instance().create(pf);
    q.uv = {0.25f, 0.75f};  // + 0.5 → white texel
    EXPECT_NEAR(f->eval(q), 1.0f, 1e-6f);
    // Unknown parameters are reported.
    Properties pu("texture", "bitmap", kLoc);
    pu.set("filename", exr, kLoc);
    pu.set("gamma", 2.2f, SourceLocation{"tex.xml", 7});
    try {
        SpectrumTextureRegistry::instance().create(pu, SpectrumKind::Reflectance);
        ADD_FAILURE();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("tex.xml:7: unknown parameter 'gamma'"), std::string::npos) << e.what();
    }
}

TEST(SceneLoaderTextures, Checkerboard) {
    Properties p("texture", "checkerboard", kLoc);
    p.set("color0", RGBValue{vec3(0.9f, 0.1f, 0.1f)}, kLoc);
    p.set("color1", RGBValue{vec3(0.1f)}, kLoc);
    p.set("to_uv", glm::scale(mat4(1.0f), vec3(2, 2, 1)), kLoc);
    const SpectrumTexturePtr t = SpectrumTextureRegistry::instance().create(p, SpectrumKind::Reflectance);
    const SampledWavelengths rgb = SampledWavelengths::rgb(defaultChannelWavelengths());
    auto at = [&](float u, float v) {
        TextureQuery q;
        q.uv = {u, v};
        return t->eval(q, rgb)[0];
    };
    EXPECT_FLOAT_EQ(at(0.1f, 0.1f), 0.9f);   // uv' = (0.2, 0.2): both low → color0
    EXPECT_FLOAT_EQ(at(0.375f, 0.1f), 0.1f); // uv' = (0.75, 0.2) → color1
    EXPECT_FLOAT_EQ(at(0.375f, 0.375f), 0.9f);
    EXPECT_FLOAT_EQ(at(0.6f, 0.1f), 0.9f);   // next period
    // Float-valued, Mitsuba 3 (eval_1): color0 where exactly one of u, v has fraction > 0.5 (issue
    // 14, item 3), the opposite of the spectrum-valued texture above.
    Properties pf("texture", "checkerboard", kLoc);
    pf.setFormatVersion(3);
    upgradeObject(pf);
    const FloatTexturePtr f = FloatTextureRegistry::instance().create(pf);
    TextureQuery q;
    q.uv = {0.75f, 0.25f};
    EXPECT_FLOAT_EQ(f->eval(q), 0.4f);  // Mitsuba defaults 0.4 / 0.2
    q.uv = {0.75f, 0.75f};
    EXPECT_FLOAT_EQ(f->eval(q), 0.2f);
    q.uv = {0.25f, 0.25f};
    EXPECT_FLOAT_EQ(f->eval(q), 0.2f);
    // Mitsuba 0.6 has one checkerboard (the spectral convention also where a float is read), and
    // its uv scale and offset (after to_uv): u' = 2u + 0.5.
    Properties po("texture", "checkerboard", kLoc);
    po.setFormatVersion(0);
    po.set("uscale", 2.0f, kLoc);
    po.set("uoffset", 0.5f, kLoc);
    upgradeObject(po);  // as the loader reads it: convention "mitsuba0.6"
    const FloatTexturePtr fo = FloatTextureRegistry::instance().create(po);
    q.uv = {0.1f, 0.25f};  // u' = 0.7, v' = 0.25 → color1
    EXPECT_FLOAT_EQ(fo->eval(q), 0.2f);
    q.uv = {0.3f, 0.25f};  // u' = 1.1 → color0
    EXPECT_FLOAT_EQ(fo->eval(q), 0.4f);
    EXPECT_EQ(Bitmap::parseFilter("ewa", kLoc), Bitmap::Filter::Bilinear);
}

TEST(SceneLoaderTextures, TexturesInSceneFiles) {
    writeEXR((texDir() / "quad.exr").string(), quad());
    const std::string ok = R"(<scene version="3.0.0">
<texture type="checkerboard" id="checks"><rgb name="color0" value="0.4"/><rgb name="color1" value="0.2"/>
  <transform name="to_uv"><scale x="8" y="8"/></transform></texture>
<shape type="sphere"><bsdf type="diffuse"><ref name="reflectance" id="checks"/></bsdf></shape>
<shape type="sphere"><bsdf type="diffuse"><texture type="bitmap" name="reflectance">
  <string name="filename" value="quad.exr"/><boolean name="raw" value="true"/>
  <string name="filter_type" value="nearest"/><string name="wrap_mode" value="mirror"/></texture></bsdf></shape>
</scene>
)";
    const std::string path = (texDir() / "textured.xml").string();
    std::ofstream(path) << ok;
    const SceneDescription s = loadScene(path);
    ASSERT_EQ(s.shapes.size(), 2u);
    EXPECT_TRUE(s.shapes[0].material);
    EXPECT_TRUE(s.shapes[1].material);

    const std::string bad = R"(<scene version="3.0.0">
<shape type="sphere"><bsdf type="diffuse"><texture type="bitmap" name="reflectance">
  <string name="filename" value="quad.exr"/>
  <string name="wrap_mode" value="tile"/></texture></bsdf></shape>
</scene>
)";
    const std::string badPath = (texDir() / "badwrap.xml").string();
    std::ofstream(badPath) << bad;
    try {
        loadScene(badPath);
        ADD_FAILURE();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("badwrap.xml:4: wrap_mode 'tile'"), std::string::npos) << e.what();
    }
    const std::string missing = "<scene version=\"3.0.0\">\n<texture type=\"bitmap\">\n<string name=\"filename\" value=\"nope.png\"/></texture>\n</scene>\n";
    const std::string missingPath = (texDir() / "missingtex.xml").string();
    std::ofstream(missingPath) << missing;
    try {
        loadScene(missingPath);
        ADD_FAILURE();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("missingtex.xml:3: file 'nope.png' not found"), std::string::npos) << e.what();
    }
}
