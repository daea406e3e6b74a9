// Texture plugins and parameters of issue 14 (normal/bump-map scenes): `rawconstant` returns its
// value raw; bitmap `format` ("auto" | "variant" | "fp16", unknown values rejected with file:line)
// and `accel`; half-precision rounding; the bitmap's exact gradient of its bilinear interpolant
// (what bumpmap differentiates, Mitsuba 3 eval_1_grad), also through to_uv.
#include <filesystem>

#include <gtest/gtest.h>

#include "core/arena.h"
#include "core/error.h"
#include "core/io/image.h"
#include "core/registry.h"
#include "materials/material.h"
#include "materials/textures/bitmap.h"
#include "materials/textures/texture.h"
#include "render/loader/scene_loader.h"

namespace iris {
namespace {

const SourceLocation kLoc{"<test>", 0};

PropertiesPtr rawConstant(PropertyValue v) {
    auto p = std::make_shared<Properties>("texture", "rawconstant", kLoc);
    p->set("value", std::move(v), kLoc);
    return p;
}

TEST(RawConstant, VectorReturnedRawInRGBMode) {
    // A value an <rgb> would turn into a reflectance spectrum (and, outside [0, 1], clamp or
    // re-fit): rawconstant returns it unchanged.
    const vec3 v(0.5f, 0.5f, 1.0f), w(-0.25f, 3.0f, 0.125f);
    for (const vec3& x : {v, w}) {
        auto tex = SpectrumTextureRegistry::instance().create(*rawConstant(VectorValue{x}), SpectrumKind::Reflectance);
        const SampledSpectrum s = tex->eval(TextureQuery{}, SampledWavelengths::rgb(defaultChannelWavelengths()));
        ASSERT_EQ(s.size(), 3);
        for (int i = 0; i < 3; ++i) EXPECT_EQ(s[i], x[i]);
        EXPECT_TRUE(tex->isConstant());
        // Spectral mode: the mean of the three values at every wavelength.
        const SampledSpectrum sp = tex->eval(TextureQuery{}, SampledWavelengths::sampleVisible(0.4f, 4));
        for (int i = 0; i < sp.size(); ++i) EXPECT_FLOAT_EQ(sp[i], (x.x + x.y + x.z) / 3.0f);
    }
    // <rgb> and <point> are accepted too; a float is replicated.
    auto rgb = SpectrumTextureRegistry::instance().create(*rawConstant(RGBValue{w}), SpectrumKind::Unbounded);
    EXPECT_EQ(rgb->eval(TextureQuery{}, SampledWavelengths::rgb(defaultChannelWavelengths()))[1], 3.0f);
    auto f = SpectrumTextureRegistry::instance().create(*rawConstant(0.75f), SpectrumKind::Reflectance);
    const SampledSpectrum fs = f->eval(TextureQuery{}, SampledWavelengths::sampleVisible(0.1f, 4));
    for (int i = 0; i < fs.size(); ++i) EXPECT_EQ(fs[i], 0.75f);
}

TEST(RawConstant, FloatTextureAndErrors) {
    auto f = FloatTextureRegistry::instance().create(*rawConstant(0.3f));
    EXPECT_EQ(f->eval(TextureQuery{}), 0.3f);
    EXPECT_EQ(f->gradient(TextureQuery{}, 1e-3f), vec2(0.0f));
    auto v = FloatTextureRegistry::instance().create(*rawConstant(VectorValue{vec3(0.0f, 0.3f, 0.6f)}));
    EXPECT_FLOAT_EQ(v->eval(TextureQuery{}), 0.3f);
    // Missing or wrongly typed value: located errors.
    auto none = std::make_shared<Properties>("texture", "rawconstant", kLoc);
    EXPECT_THROW(FloatTextureRegistry::instance().create(*none), Error);
    EXPECT_THROW(FloatTextureRegistry::instance().create(*rawConstant(std::string("red"))), Error);
}

TEST(RawConstant, LoadsTheIdentityNormalMapScene) {
    // test_normalmap_identity_roughconductor_path.xml:8 stopped at "unknown texture type".
    const std::string xml = R"(<scene version="2.1.0">
  <bsdf type="normalmap" id="nm">
    <texture name="normalmap" type="rawconstant">
      <vector name="value" value="0.5, 0.5, 1.0"/>
    </texture>
    <bsdf type="roughconductor"><string name="material" value="Al"/></bsdf>
  </bsdf>
  <shape type="sphere"><ref id="nm"/></shape>
</scene>)";
    const SceneDescription scene = loadSceneFromString(xml, ".");
    ASSERT_EQ(scene.shapes.size(), 1u);
    EXPECT_TRUE(scene.shapes[0].material);
}

TEST(Bitmap, RoundToHalf) {
    EXPECT_EQ(Bitmap::roundToHalf(1.0f), 1.0f);
    EXPECT_EQ(Bitmap::roundToHalf(0.1f), 0.0999755859375f);         // 0x2E66
    EXPECT_EQ(Bitmap::roundToHalf(1.0f / 3.0f), 0.333251953125f);   // 0x3555
    EXPECT_EQ(Bitmap::roundToHalf(-2.0f / 3.0f), -0.66650390625f);  // 0xB955
    EXPECT_EQ(Bitmap::roundToHalf(1.0f + 1.0f / 2048.0f), 1.0f);    // tie → even
    EXPECT_EQ(Bitmap::roundToHalf(1.0f + 3.0f / 2048.0f), 1.0f + 2.0f / 1024.0f);  // tie → even (up)
    EXPECT_EQ(Bitmap::roundToHalf(65504.0f), 65504.0f);
    EXPECT_EQ(Bitmap::roundToHalf(65519.0f), 65504.0f);
    EXPECT_TRUE(std::isinf(Bitmap::roundToHalf(65520.0f)));
    EXPECT_EQ(Bitmap::roundToHalf(std::ldexp(1.0f, -24)), std::ldexp(1.0f, -24));  // smallest subnormal
    EXPECT_EQ(Bitmap::roundToHalf(std::ldexp(1.0f, -25)), 0.0f);                   // tie → even (0)
    EXPECT_EQ(Bitmap::roundToHalf(std::ldexp(3.0f, -26)), std::ldexp(1.0f, -24));
    EXPECT_EQ(Bitmap::roundToHalf(std::ldexp(1.5f, -20)), std::ldexp(1.5f, -20));  // subnormal, exact
    EXPECT_TRUE(std::isnan(Bitmap::roundToHalf(std::nanf(""))));
    // Every 8-bit value k/255 is within half a half-ulp (2^-12 relative) of its rounding.
    for (int k = 1; k < 256; ++k) {
        const float x = float(k) / 255.0f;
        EXPECT_LE(std::abs(Bitmap::roundToHalf(x) - x), std::ldexp(x, -11)) << k;
    }
}

std::filesystem::path texDir() {
    auto d = std::filesystem::temp_directory_path() / "iris_test_texture_plugins";
    std::filesystem::create_directories(d);
    return d;
}

std::string bitmapScene(const std::string& format) {
    return R"(<scene version="3.0.0">
  <bsdf type="diffuse" id="d">
    <texture type="bitmap" name="reflectance">
      <string name="filename" value="thirds.exr"/>
      <boolean name="raw" value="true"/>
      <boolean name="accel" value="false"/>
)" + (format.empty() ? std::string() : "      <string name=\"format\" value=\"" + format + "\"/>\n") +
           R"(    </texture>
  </bsdf>
  <shape type="sphere"><ref id="d"/></shape>
</scene>)";
}

TEST(Bitmap, FormatParameter) {
    Image img(2, 2, 3);
    for (float& v : img.pixels) v = 1.0f / 3.0f;
    writeEXR((texDir() / "thirds.exr").string(), img);
    const SampledWavelengths rgbWl = SampledWavelengths::rgb(defaultChannelWavelengths());
    auto valueWith = [&](const std::string& format) {
        const SceneDescription s = loadSceneFromString(bitmapScene(format), texDir().string());
        // The diffuse reflectance at any point: ρ/π · π.
        Arena arena;
        SampledWavelengths wl = rgbWl;
        const BSDF* b = s.shapes.at(0).material->getBSDF(ShadingPoint{}, wl, arena);
        return b->eval(vec3(0, 0, 1), vec3(0, 0, 1), TransportMode::Radiance)[0] * kPi;
    };
    EXPECT_NEAR(valueWith(""), 1.0f / 3.0f, 1e-7f);  // auto: float storage (see bitmap_texture.cpp)
    EXPECT_NEAR(valueWith("variant"), 1.0f / 3.0f, 1e-7f);
    EXPECT_NEAR(valueWith("fp16"), 0.333251953125f, 1e-7f);  // rounded to half (0x3555)
    try {
        loadSceneFromString(bitmapScene("fp32"), texDir().string());
        ADD_FAILURE() << "expected an error for format fp32";
    } catch (const Error& e) {
        const std::string msg = e.what();
        EXPECT_NE(msg.find("<string>:7:"), std::string::npos) << msg;
        EXPECT_NE(msg.find("format 'fp32'"), std::string::npos) << msg;
    }
}

TEST(Bitmap, GradientOfTheBilinearInterpolant) {
    // A 4×2 grey image; inside each bilinear cell the lookup is bilinear in (u, v), and the
    // gradient is its exact derivative: compared with central differences well inside a cell.
    Image img(4, 2, 1);
    const float vals[8] = {0.1f, 0.7f, 0.2f, 0.9f, 0.4f, 0.3f, 0.8f, 0.0f};
    for (int i = 0; i < 8; ++i) img.pixels[size_t(i)] = vals[i];
    const Bitmap b(img);
    using F = Bitmap::Filter;
    using W = Bitmap::Wrap;
    for (const vec2& uv : {vec2(0.3f, 0.4f), vec2(0.55f, 0.6f), vec2(0.05f, 0.2f), vec2(0.95f, 0.9f)}) {
        const vec2 g = b.gradientGrey(uv, F::Bilinear, W::Repeat);
        const float d = 1e-3f;
        const float gu = (b.lookupGrey(uv + vec2(d, 0), F::Bilinear, W::Repeat) -
                          b.lookupGrey(uv - vec2(d, 0), F::Bilinear, W::Repeat)) / (2 * d);
        const float gv = (b.lookupGrey(uv + vec2(0, d), F::Bilinear, W::Repeat) -
                          b.lookupGrey(uv - vec2(0, d), F::Bilinear, W::Repeat)) / (2 * d);
        EXPECT_NEAR(g.x, gu, 2e-3f) << uv.x << "," << uv.y;
        EXPECT_NEAR(g.y, gv, 2e-3f) << uv.x << "," << uv.y;
    }
    // One value by hand: uv = (0.3, 0.4) → pixel (1.2, 0.8) − 0.5 = (0.7, 0.3) in the cell of
    // texels x 0–1, y 0–1: ∂/∂x = 0.7·(0.7 − 0.1) + 0.3·(0.3 − 0.4) = 0.39, times width 4.
    EXPECT_NEAR(b.gradientGrey(vec2(0.3f, 0.4f), F::Bilinear, W::Repeat).x, 4 * 0.39f, 1e-5f);
    EXPECT_EQ(b.gradientGrey(vec2(0.3f, 0.4f), F::Nearest, W::Repeat), vec2(0.0f));
}

TEST(Bitmap, FloatTextureGradientThroughToUV) {
    // A u ramp image (4×1, values 0, 1, 2, 3 at texel centres: slope 4 per unit u inside) read
    // with to_uv scaling u by 0.5: the gradient with respect to the surface u halves.
    Image img(4, 1, 1);
    for (int i = 0; i < 4; ++i) img.pixels[size_t(i)] = float(i);
    writeEXR((texDir() / "ramp.exr").string(), img);
    auto tex = std::make_shared<Properties>("texture", "bitmap", kLoc);
    tex->set("filename", (texDir() / "ramp.exr").string(), kLoc);
    tex->set("raw", true, kLoc);
    auto plain = FloatTextureRegistry::instance().create(*tex);
    TextureQuery q;
    q.uv = vec2(0.5f, 0.5f);
    EXPECT_NEAR(plain->gradient(q, 1e-3f).x, 4.0f, 1e-5f);
    EXPECT_NEAR(plain->gradient(q, 1e-3f).y, 0.0f, 1e-6f);
    tex->set("to_uv", glm::scale(mat4(1.0f), vec3(0.5f, 1.0f, 1.0f)), kLoc);
    auto scaled = FloatTextureRegistry::instance().create(*tex);
    q.uv = vec2(1.0f, 0.5f);  // → u' = 0.5
    EXPECT_NEAR(scaled->gradient(q, 1e-3f).x, 2.0f, 1e-5f);
}

}  // namespace
}  // namespace iris
