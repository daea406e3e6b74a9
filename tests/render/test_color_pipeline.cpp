// End-to-end colour convention: an RGB white light on an RGB white diffuse surface renders white
// (linear Rec.709 (1,1,1) after XYZ → OCIO), in spectral mode, and identically in RGB mode.
#include <gtest/gtest.h>

#include "render/film.h"
#include "render/renderer.h"
#include "render/scene.h"
#include "tests/support/render_test_scenes.h"
#include "spectral/color_management.h"

using namespace iris;
using namespace iris::testing;

namespace {

/// White sphere in a white environment, both given as RGB triples or as plain floats.
SceneDescription whiteOnWhite(bool asFloats) {
    SceneDescription d = furnaceScene(1.0f, 16, 256);
    Properties bsdf("bsdf", "diffuse", SourceLocation{"<test>", 0});
    if (asFloats)
        bsdf.set("reflectance", 1.0f, SourceLocation{"<test>", 0});
    else
        bsdf.set("reflectance", RGBValue{vec3(1.0f)}, SourceLocation{"<test>", 0});
    d.shapes[0].material = MaterialRegistry::instance().create(bsdf);
    Properties env("emitter", "constant", SourceLocation{"<test>", 0});
    if (asFloats)
        env.set("radiance", 1.0f, SourceLocation{"<test>", 0});
    else
        env.set("radiance", RGBValue{vec3(1.0f)}, SourceLocation{"<test>", 0});
    d.lights = {LightRegistry::instance().create(env)};
    return d;
}

/// Mean and standard error of each linear Rec.709 channel over all pixels.
void meanRgb(const Film& film, bool rgbMode, vec3& mean, vec3& stderr_) {
    std::vector<float> px = film.meanImage();
    if (!rgbMode) ColorManager().convert(px.data(), px.size() / 3, kColorSpaceXYZ, kColorSpaceLinearRec709);
    const size_t n = px.size() / 3;
    dvec3 s(0.0), s2(0.0);
    for (size_t i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c) {
            s[c] += px[3 * i + c];
            s2[c] += double(px[3 * i + c]) * px[3 * i + c];
        }
    for (int c = 0; c < 3; ++c) {
        mean[c] = float(s[c] / n);
        stderr_[c] = float(std::sqrt(std::max(0.0, s2[c] / n - sqr(s[c] / n)) / n));
    }
}

}  // namespace

TEST(ColorPipeline, RgbWhiteLightOnRgbWhiteWallIsWhite) {
  for (const bool asFloats : {false, true}) {
    const Scene scene(whiteOnWhite(asFloats));
    for (const bool rgbMode : {false, true}) {
        RenderOptions opt;
        opt.rgbMode = rgbMode;
        opt.spectralSamples = 4;
        opt.seed = 3;
        Film film(16, 16);
        Renderer(scene, opt).render(film);
        vec3 mean, se;
        meanRgb(film, rgbMode, mean, se);
        for (int c = 0; c < 3; ++c) {
            // The D65 white point maps to (1,1,1) up to the rounding of the published matrix (1e-3).
            EXPECT_NEAR(mean[c], 1.0f, 5 * se[c] + 2e-3f)
                << (rgbMode ? "rgb" : "spectral") << (asFloats ? " floats" : " rgb values") << " channel " << c;
        }
        if (rgbMode) EXPECT_EQ(film.pixel(0, 0), vec3(1.0f));  // background: radiance exactly (1,1,1)
    }
  }
}
