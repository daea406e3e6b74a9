// Mitsuba 0.6's ldrfilm: its parameters are read (0.6 names) and the tone map gives the expected
// code values; bad parameters are errors.
#include <gtest/gtest.h>

#include "render/films/ldr_tonemap.h"
#include "render/loader/scene_loader.h"

using namespace iris;

namespace {
SceneDescription loadFilm(const std::string& filmBody) {
    return loadSceneFromString("<scene version=\"0.6.0\"><sensor type=\"perspective\"><film type=\"ldrfilm\">"
                               "<integer name=\"width\" value=\"4\"/><integer name=\"height\" value=\"2\"/>" +
                                   filmBody + "</film></sensor></scene>",
                               ".");
}
}  // namespace

TEST(LdrFilm, ReadsMitsuba06Parameters) {
    const SceneDescription s = loadFilm(R"(<float name="gamma" value="2.2"/><float name="exposure" value="1"/>
        <string name="tonemapMethod" value="reinhard"/><float name="reinhardKey" value="0.3"/><boolean name="banner" value="false"/>)");
    ASSERT_TRUE(s.camera.ldr);
    EXPECT_EQ(s.camera.width, 4);
    EXPECT_EQ(s.camera.ldr->method, LdrSettings::Method::Reinhard);
    EXPECT_FLOAT_EQ(s.camera.ldr->gamma, 2.2f);
    EXPECT_FLOAT_EQ(s.camera.ldr->exposure, 1.0f);
    EXPECT_FLOAT_EQ(s.camera.ldr->key, 0.3f);
    EXPECT_FALSE(loadSceneFromString("<scene version=\"3.0.0\"><sensor type=\"perspective\"/></scene>", ".").camera.ldr);
    EXPECT_THROW(loadFilm(R"(<string name="tonemapMethod" value="filmic"/>)"), Error);
    EXPECT_THROW(loadFilm(R"(<float name="gamma" value="0"/>)"), Error);
}

TEST(LdrFilm, GammaExposureAndSrgbCurve) {
    LdrSettings s;
    s.gamma = 2.2f;
    s.exposure = 1.0f;
    float px[6] = {0.25f, 0.0f, 2.0f, 0.1f, 0.1f, 0.1f};
    applyLdrTonemap(s, px, 2);
    EXPECT_NEAR(px[0], std::pow(0.5f, 1.0f / 2.2f), 1e-6);  // 0.25 · 2^1 = 0.5
    EXPECT_EQ(px[1], 0.0f);
    EXPECT_EQ(px[2], 1.0f);  // clamped
    LdrSettings srgb;        // gamma −1: the sRGB curve
    float q[3] = {0.002f, 0.5f, 1.0f};
    applyLdrTonemap(srgb, q, 1);
    EXPECT_NEAR(q[0], 12.92f * 0.002f, 1e-6);
    EXPECT_NEAR(q[1], 1.055f * std::pow(0.5f, 1.0f / 2.4f) - 0.055f, 1e-6);
    EXPECT_NEAR(q[2], 1.0f, 1e-6);
}

TEST(LdrFilm, ReinhardMapsTheLogAverageToTheKey) {
    // A uniform grey image: log-average = its luminance, so every pixel maps to a (1 + a / Lw²)
    // / (1 + a) with Lw = a (burn 0: the brightest pixel is the white point) before the curve.
    LdrSettings s;
    s.method = LdrSettings::Method::Reinhard;
    s.gamma = 1.0f;
    std::vector<float> img(3 * 4, 0.7f);
    applyLdrTonemap(s, img.data(), 4);
    const float a = 0.18f, expected = a * (1 + a / (a * a)) / (1 + a);
    for (float v : img) EXPECT_NEAR(v, expected, 2e-4f);
}
