// --wavelength-sampling independent (RenderOptions::independentWavelengths): unbiased like the
// hero scheme, but without its stratification, so its colour noise is larger (Wilkie et al.,
// "Hero Wavelength Spectral Sampling", EGSR 2014, §4).
#include <gtest/gtest.h>

#include <cmath>

#include "render/renderer.h"
#include "render/scene.h"
#include "tests/support/render_test_scenes.h"

using namespace iris;

namespace {

struct PixelStats {
    double meanY = 0, varY = 0;  // over the pixels, of the per-pixel means
};

/// The furnace (albedo 0.8 sphere in an environment of radiance 1·D65): every pixel's expected Y
/// is 1 (background) or 0.8 (sphere, which is convex: one bounce sees only the environment).
PixelStats render(bool independent) {
    const Scene scene(iris::testing::furnaceScene(0.8f, 16, 16));
    RenderOptions opt;
    opt.spectralSamples = 4;
    opt.seed = 11;
    opt.independentWavelengths = independent;
    Film film(16, 16);
    Renderer(scene, opt).render(film);
    const std::vector<float> img = film.meanImage();
    PixelStats s;
    int n = 0;
    double sumErr2 = 0, sumErr = 0;
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x) {
            const double Y = img[3 * size_t(y * 16 + x) + 1];
            const double expect = std::abs(Y - 0.8) < std::abs(Y - 1.0) ? 0.8 : 1.0;
            sumErr += Y - expect;
            sumErr2 += (Y - expect) * (Y - expect);
            ++n;
        }
    s.meanY = sumErr / n;
    s.varY = sumErr2 / n - s.meanY * s.meanY;
    return s;
}

}  // namespace

TEST(WavelengthSampling, IndependentIsUnbiasedButNoisierThanHero) {
    const PixelStats hero = render(false), indep = render(true);
    // Unbiased: the mean error over 256 pixels is within 4 standard errors of 0.
    EXPECT_LT(std::abs(hero.meanY), 4 * std::sqrt(hero.varY / 256) + 1e-6);
    EXPECT_LT(std::abs(indep.meanY), 4 * std::sqrt(indep.varY / 256) + 1e-6);
    // Not the same estimator: the option changes the image, and stratification lowers the noise.
    EXPECT_NE(hero.varY, indep.varY);
    EXPECT_LT(hero.varY, indep.varY);
    std::printf("per-pixel variance of Y: hero %.3g, independent %.3g\n", hero.varY, indep.varY);
}
