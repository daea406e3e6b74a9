// Bitmap textures in spectral mode: large images go through the shared RGB→spectrum grid; the
// upsampled spectrum of a texel still projects back onto the texel's RGB.
#include <gtest/gtest.h>

#include "core/io/image.h"
#include "core/properties.h"
#include "core/registry.h"
#include "materials/textures/texture.h"
#include "spectral/color_space.h"

using namespace iris;

TEST(BitmapSpectral, LargeImageUsesGridAndRoundTrips) {
    const int w = 100, h = 100;  // 10⁴ texels: above the per-texel fit limit
    const vec3 c(0.7f, 0.3f, 0.15f);
    Image img(w, h, 3);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int k = 0; k < 3; ++k) img.at(x, y, k) = c[k];
    const std::string path = ::testing::TempDir() + "iris_bitmap_grid_test.exr";
    writeEXR(path, img);
    Properties p("texture", "bitmap", SourceLocation{"<test>", 0});
    p.set("filename", path, SourceLocation{});
    const SpectrumTexturePtr tex = SpectrumTextureRegistry::instance().create(p, SpectrumKind::Reflectance);
    TextureQuery q;
    q.uv = vec2(0.37f, 0.61f);
    // RGB mode: the texel unchanged.
    const SampledSpectrum rgb = tex->eval(q, SampledWavelengths::rgb(defaultChannelWavelengths()));
    for (int k = 0; k < 3; ++k) EXPECT_FLOAT_EQ(rgb[k], c[k]);
    // Spectral mode: a proper reflectance whose projection is the texel's RGB.
    auto f = [&](float lambda) {
        SampledWavelengths wl = SampledWavelengths::sampleUniform((lambda - kLambdaMin) / (kLambdaMax - kLambdaMin), 1);
        return tex->eval(q, wl)[0];
    };
    for (float l = 360; l < 830; l += 10) {
        const float v = f(l);
        EXPECT_GE(v, 0.0f);
        EXPECT_LE(v, 1.0f);
    }
    const vec3 back = rgbProjection(f, SpectrumKind::Reflectance);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(back[k], c[k], 2e-3f);
    std::remove(path.c_str());
}
