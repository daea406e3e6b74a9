// RGB → spectrum upsampling (Jakob & Hanika 2019): the round trip RGB → spectrum → RGB, bounds,
// greys as exact constants, and the bit-exact RGB mode.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>

#include "core/error.h"
#include "core/rng.h"
#include "spectral/color_space.h"
#include "spectral/rgb_spectrum.h"
#include "spectral/rgb_spectrum_grid.h"
#include "spectral/spectrum_factory.h"

using namespace iris;

namespace {
std::vector<vec3> colourGrid() {
    const float levels[] = {0.05f, 0.2f, 0.5f, 0.8f, 0.95f};
    std::vector<vec3> g;
    for (float r : levels)
        for (float gr : levels)
            for (float b : levels) g.emplace_back(r, gr, b);
    return g;
}
float maxAbsDiff(const vec3& a, const vec3& b) {
    const vec3 d = glm::abs(a - b);
    return std::max({d.x, d.y, d.z});
}
}  // namespace

TEST(RgbUpsampling, ReflectanceRoundTripAndBounds) {
    float worst = 0;
    vec3 worstColour(0.0f);
    for (const vec3& rgb : colourGrid()) {
        if (rgb.x == rgb.y && rgb.y == rgb.z) continue;  // greys: GreysAreExactConstants
        const SpectrumPtr s = makeRGBSpectrum(rgb, SpectrumKind::Reflectance);
        const vec3 back = rgbProjection([&](float l) { return s->eval(l); }, SpectrumKind::Reflectance);
        const float err = maxAbsDiff(back, rgb);
        EXPECT_LT(err, 1e-3f) << "rgb " << rgb.x << " " << rgb.y << " " << rgb.z;
        if (err > worst) worst = err, worstColour = rgb;
        for (int l = 360; l <= 830; l += 5) {
            const float v = s->eval(float(l));
            ASSERT_GE(v, 0.0f);
            ASSERT_LE(v, 1.0f);
            ASSERT_LE(v, s->maxValue() + 1e-6f);
        }
        EXPECT_LE(s->maxValue(), 1.0f);
    }
    // Reported in docs/spectral.md.
    std::printf("[ measured ] worst reflectance round-trip error over the 120 non-grey grid colours: %.3g at (%g, %g, %g)\n",
                worst, worstColour.x, worstColour.y, worstColour.z);
}

TEST(RgbUpsampling, RandomColoursRoundTrip) {
    // 500 random colours in [0.02, 0.98]³ (fixed seed): every one within 1e-3.
    Pcg32 rng(2019, 5);
    float worst = 0;
    for (int k = 0; k < 500; ++k) {
        const vec3 rgb(0.02f + 0.96f * rng.uniform(), 0.02f + 0.96f * rng.uniform(), 0.02f + 0.96f * rng.uniform());
        const RGBSpectrum s(rgb, SpectrumKind::Reflectance);
        const vec3 back = rgbProjection([&](float l) { return s.eval(l); }, SpectrumKind::Reflectance);
        const float err = maxAbsDiff(back, rgb);
        EXPECT_LT(err, 1e-3f) << rgb.x << " " << rgb.y << " " << rgb.z;
        worst = std::max(worst, err);
    }
    std::printf("[ measured ] worst reflectance round-trip error over 500 random colours in [0.02, 0.98]^3: %.3g\n", worst);
}

TEST(RgbUpsampling, ExtremeAndDarkColours) {
    // Gamut corners and near-black colours: still reproduced, finite, within [0, 1], and dark
    // colours have no bright invisible lobe (max value of the same order as the colour).
    const vec3 colours[] = {vec3(1, 0, 0),    vec3(0, 1, 0),       vec3(0, 0, 1),        vec3(1, 1, 0),
                            vec3(0, 0.5f, 0.5f), vec3(1e-6f, 0, 0), vec3(0.001f, 0, 0), vec3(0.01f, 0.001f, 0),
                            vec3(0.002f, 0.001f, 0.0005f), vec3(0.049f, 0.0f, 0.02f)};
    for (const vec3& rgb : colours) {
        const RGBSpectrum s(rgb, SpectrumKind::Reflectance);
        const vec3 back = rgbProjection([&](float l) { return s.eval(l); }, SpectrumKind::Reflectance);
        EXPECT_LT(maxAbsDiff(back, rgb), 1e-5f) << rgb.x << " " << rgb.y << " " << rgb.z;
        for (int l = 360; l <= 830; ++l) {
            const float v = s.eval(float(l));
            ASSERT_TRUE(std::isfinite(v));
            ASSERT_GE(v, 0.0f);
            ASSERT_LE(v, 1.0f);
        }
        const float m = std::max({rgb.x, rgb.y, rgb.z});
        if (m < RGBSpectrum::kDarkLevel) EXPECT_LE(s.maxValue(), m / RGBSpectrum::kDarkLevel) << rgb.x;
    }
    // Out-of-range reflectances are clamped for the spectral curve (RGB mode keeps the triple).
    const RGBSpectrum over(vec3(1.5f, -0.2f, 0.5f), SpectrumKind::Reflectance);
    const vec3 back = rgbProjection([&](float l) { return over.eval(l); }, SpectrumKind::Reflectance);
    EXPECT_LT(maxAbsDiff(back, vec3(1.0f, 0.0f, 0.5f)), 1e-5f);
    EXPECT_EQ(over.rgbValue(), vec3(1.5f, -0.2f, 0.5f));
}

TEST(RgbUpsampling, GreysAreExactConstants) {
    for (float g : {0.0f, 0.05f, 0.18f, 0.5f, 0.9f, 1.0f}) {
        const SpectrumPtr s = makeRGBSpectrum(vec3(g), SpectrumKind::Reflectance);
        for (int l = 360; l <= 830; l += 7) EXPECT_EQ(s->eval(float(l)), g);
        EXPECT_EQ(s->maxValue(), g);
        const vec3 back = rgbProjection([&](float l) { return s->eval(l); }, SpectrumKind::Reflectance);
        EXPECT_LT(maxAbsDiff(back, vec3(g)), 1e-3f);
    }
    // Unbounded greys keep their value, including negatives and values above 1.
    for (float g : {-0.5f, 0.0f, 1.0f, 2.5f}) {
        const SpectrumPtr s = makeRGBSpectrum(vec3(g), SpectrumKind::Unbounded);
        EXPECT_EQ(s->eval(500.0f), g);
    }
}

TEST(RgbUpsampling, UnboundedRoundTrip) {
    for (const vec3& rgb : {vec3(2.0f, 1.0f, 0.5f), vec3(0.3f, 1.6f, 0.9f), vec3(0.1f, 0.2f, 4.0f), vec3(1.5f, 1.45f, 1.4f)}) {
        const SpectrumPtr s = makeRGBSpectrum(rgb, SpectrumKind::Unbounded);
        const vec3 back = rgbProjection([&](float l) { return s->eval(l); }, SpectrumKind::Reflectance);
        const float m = std::max({rgb.x, rgb.y, rgb.z});
        EXPECT_LT(maxAbsDiff(back, rgb), 1e-3f * m) << rgb.x << " " << rgb.y << " " << rgb.z;
        for (int l = 360; l <= 830; l += 5) {
            EXPECT_GE(s->eval(float(l)), 0.0f);
            EXPECT_LE(s->eval(float(l)), s->maxValue() * (1 + 1e-6f));
        }
    }
}

TEST(RgbUpsampling, IlluminantConvention) {
    // RGB (1,1,1) emits exactly D65 with Y = 1.
    const SpectrumPtr white = makeRGBSpectrum(vec3(1.0f), SpectrumKind::Illuminant);
    const SpectrumPtr d65 = makeD65Spectrum();
    for (int l = 360; l <= 830; l += 3) EXPECT_FLOAT_EQ(white->eval(float(l)), d65->eval(float(l)));
    const vec3 whiteRGB = rgbProjection([&](float l) { return white->eval(l); }, SpectrumKind::Illuminant);
    EXPECT_LT(maxAbsDiff(whiteRGB, vec3(1.0f)), 1e-3f);
    // Coloured emitters: the plain projection of the emitted spectrum reproduces the RGB.
    for (const vec3& rgb : {vec3(5.0f, 2.0f, 1.0f), vec3(0.2f, 0.8f, 0.3f), vec3(0.05f, 0.05f, 0.9f)}) {
        const SpectrumPtr s = makeRGBSpectrum(rgb, SpectrumKind::Illuminant);
        const vec3 back = rgbProjection([&](float l) { return s->eval(l); }, SpectrumKind::Illuminant);
        const float m = std::max({rgb.x, rgb.y, rgb.z});
        EXPECT_LT(maxAbsDiff(back, rgb), 1e-3f * m) << rgb.x << " " << rgb.y << " " << rgb.z;
    }
}

TEST(RgbUpsampling, RgbModeIsBitExact) {
    const SampledWavelengths wl = SampledWavelengths::rgb(defaultChannelWavelengths());
    const vec3 triples[] = {vec3(0.123456789f, 0.987654321f, 0.5f), vec3(3.0f, -0.25f, 1e-7f), vec3(1.0f), vec3(0.0f)};
    for (const vec3& rgb : triples) {
        for (SpectrumKind kind : {SpectrumKind::Reflectance, SpectrumKind::Unbounded, SpectrumKind::Illuminant}) {
            const SpectrumPtr s = makeRGBSpectrum(rgb, kind);
            const SampledSpectrum v = s->sample(wl);
            ASSERT_EQ(v.size(), 3);
            for (int i = 0; i < 3; ++i) EXPECT_EQ(v[i], rgb[i]);
            EXPECT_EQ(s->rgbValue(), rgb);
        }
    }
}

TEST(RgbUpsampling, SpectralSampleMatchesEval) {
    const SpectrumPtr s = makeRGBSpectrum(vec3(0.7f, 0.3f, 0.1f), SpectrumKind::Reflectance);
    const SampledWavelengths wl = SampledWavelengths::sampleVisible(0.37f, 8);
    const SampledSpectrum v = s->sample(wl);
    for (int i = 0; i < 8; ++i) EXPECT_EQ(v[i], s->eval(wl.lambda(i)));
    // A reddish reflectance is larger at long wavelengths than at short ones.
    EXPECT_GT(s->eval(650.0f), s->eval(450.0f));
}

TEST(RgbUpsampling, NonFiniteInputIsAnError) {
    EXPECT_THROW(makeRGBSpectrum(vec3(NAN, 0.5f, 0.5f), SpectrumKind::Reflectance), Error);
}

TEST(RgbUpsampling, LazyGridForTexturesReproducesRgb) {
    const bool builtBefore = RGBSpectrumGrid::built();
    const auto t0 = std::chrono::steady_clock::now();
    const RGBSpectrumGrid& grid = RGBSpectrumGrid::instance();
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    EXPECT_TRUE(RGBSpectrumGrid::built());
    if (!builtBefore) std::printf("[ measured ] RGBSpectrumGrid build (%d^3 fits): %.3f s\n", RGBSpectrumGrid::kResolution, seconds);
    Pcg32 rng(77, 1);
    float worst = 0;
    for (int k = 0; k < 300; ++k) {
        const vec3 rgb(rng.uniform(), rng.uniform(), rng.uniform());
        const vec3 back = rgbProjection([&](float l) { return grid.reflectance(rgb, l); }, SpectrumKind::Reflectance);
        const float err = maxAbsDiff(back, rgb);
        EXPECT_LT(err, 1e-3f) << rgb.x << " " << rgb.y << " " << rgb.z;
        worst = std::max(worst, err);
        for (int l = 360; l <= 830; l += 10) {
            const float v = grid.reflectance(rgb, float(l));
            ASSERT_GE(v, 0.0f);
            ASSERT_LE(v, 1.0f + 1e-6f);
        }
    }
    std::printf("[ measured ] worst grid round-trip error over 300 random colours in [0,1]^3: %.3g\n", worst);
    // At a node the grid is that node's own fitted spectrum.
    const vec3 node(4.0f / 16, 8.0f / 16, 12.0f / 16);
    const RGBSpectrum direct(node, SpectrumKind::Reflectance);
    for (int l = 360; l <= 830; l += 10) EXPECT_NEAR(grid.reflectance(node, float(l)), direct.eval(float(l)), 1e-6f);
    // Sampled forms: spectral = per-wavelength values, RGB mode = the triple, every kind.
    const SampledWavelengths wl = SampledWavelengths::sampleVisible(0.61f, 8);
    const vec3 c(0.3f, 0.6f, 0.2f);
    const SampledSpectrum s = grid.sample(c, SpectrumKind::Reflectance, wl);
    for (int i = 0; i < 8; ++i) EXPECT_FLOAT_EQ(s[i], grid.reflectance(c, wl.lambda(i)));
    const SampledSpectrum u = grid.sample(2.0f * c, SpectrumKind::Unbounded, wl);
    const SampledSpectrum uRef = grid.reflectance(c / 0.6f, wl) * 1.2f;
    for (int i = 0; i < 8; ++i) EXPECT_NEAR(u[i], uRef[i], 1e-5f);
    const SampledWavelengths rgbWl = SampledWavelengths::rgb(defaultChannelWavelengths());
    for (SpectrumKind kind : {SpectrumKind::Reflectance, SpectrumKind::Unbounded, SpectrumKind::Illuminant}) {
        const SampledSpectrum r = grid.sample(vec3(0.1f, 2.0f, 0.3f), kind, rgbWl);
        EXPECT_EQ(r[0], 0.1f);
        EXPECT_EQ(r[1], 2.0f);
        EXPECT_EQ(r[2], 0.3f);
    }
    // Illuminant white: exactly D65 with Y = 1, like makeRGBSpectrum.
    const SpectrumPtr d65 = makeD65Spectrum();
    const SampledSpectrum w = grid.sample(vec3(1.0f), SpectrumKind::Illuminant, wl);
    for (int i = 0; i < 8; ++i) EXPECT_NEAR(w[i], d65->eval(wl.lambda(i)), 1e-6f * d65->maxValue());
}
