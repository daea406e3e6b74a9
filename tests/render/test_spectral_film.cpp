// The spectral film of --spectral-output (render/spectral_film.h): each bin estimates the mean
// radiance over the bin, colour derived from the bins agrees with the colour film, and the file
// round-trips through the OpenEXR spectral layout.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "core/error.h"
#include "core/io/image.h"
#include "core/io/spectral_layout.h"
#include "render/renderer.h"
#include "render/scene.h"
#include "render/spectral_film.h"
#include "spectral/xyz.h"
#include "tests/support/app_runner.h"
#include "tests/support/render_test_scenes.h"

using namespace iris;

namespace {

/// Feed M stratified hero samples (N wavelengths each) of the spectrum f into pixel (0, 0).
template <typename F>
void feed(SpectralFilm& film, F&& f, int M, int N, dvec3* directXyz = nullptr) {
    dvec3 sum(0.0);
    for (int k = 0; k < M; ++k) {
        const SampledWavelengths wl = SampledWavelengths::sampleVisible((float(k) + 0.5f) / float(M), N);
        SampledSpectrum L(N);
        for (int i = 0; i < N; ++i) L[i] = f(wl.lambda(i));
        film.addSample(0, 0, L, wl);
        sum += dvec3(toXYZ(L, wl));
    }
    if (directXyz) *directXyz = sum / double(M);
}

}  // namespace

TEST(SpectralFilm, ConstantSpectrumGivesItsValueInEveryBin) {
    // E[L/(N p Δ)] over the bin = L: with 100000 stratified hero samples every 5 nm bin is within 2 %
    // (a missing 1/N or 1/Δ would be off by 4x or 5x).
    SpectralFilm film(1, 1, SpectralBins(5.0));
    feed(film, [](float) { return 0.75f; }, 100000, 4);
    const Image img = film.image();
    ASSERT_EQ(img.channels, 94);
    for (int b = 0; b < img.channels; ++b) EXPECT_NEAR(img.pixels[size_t(b)], 0.75f, 0.015f) << img.channelNames[size_t(b)];
}

TEST(SpectralFilm, ColourFromTheBinsAgreesWithTheDirectXyzEstimate) {
    // A smooth spectrum: the XYZ of the bins and toXYZ's estimate from the same samples both
    // converge to the exact integral; binning adds O(Δ²) for a non-constant spectrum.
    auto f = [](float l) { return 0.2f + 0.8f * std::exp(-0.5f * std::pow((l - 600.0f) / 60.0f, 2.0f)); };
    SpectralFilm film(1, 1, SpectralBins(5.0));
    dvec3 direct;
    feed(film, f, 40000, 8, &direct);
    const dvec3 exact = integrateXYZ(f);
    const Image xyz = xyzImage(spectralChannels(film.image(), "<film>"));
    const dvec3 binned(xyz.pixels[0], xyz.pixels[1], xyz.pixels[2]);
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(direct[c], exact[c], 2e-3 * exact[c]) << c;
        EXPECT_NEAR(binned[c], exact[c], 2e-3 * exact[c]) << c;
    }
}

TEST(SpectralFilm, RenderedBinsMatchTheColourFilmAndCountEverySample) {
    SceneDescription d = iris::testing::furnaceScene(0.8f, 16, 64);
    const Scene scene(std::move(d));
    RenderOptions opt;
    opt.spectralSamples = 4;
    opt.seed = 3;
    const Renderer renderer(scene, opt);
    Film film(16, 16);
    SpectralFilm spectral(16, 16, SpectralBins(10.0));
    renderer.render(film, nullptr, &spectral);
    const Image xyz = xyzImage(spectralChannels(spectral.image(), "<film>"));
    const std::vector<float> direct = film.meanImage();
    // Image means of Y: the same samples, binned or not; the difference is the binning noise of
    // 16·16·64 samples (measured ~1e-3 relative), far below 1 %.
    double yBins = 0, yDirect = 0;
    for (size_t p = 0; p < xyz.pixelCount(); ++p) {
        yBins += xyz.pixels[3 * p + 1];
        yDirect += direct[3 * p + 1];
        EXPECT_EQ(spectral.sampleCount(int(p % 16), int(p / 16)), film.sampleCount(int(p % 16), int(p / 16)));
    }
    EXPECT_GT(yDirect, 0.0);
    EXPECT_NEAR(yBins / yDirect, 1.0, 0.01);
}

TEST(SpectralFilm, RgbModeAndMismatchedSizesAreRejected) {
    const Scene scene(iris::testing::furnaceScene(0.5f, 8, 1));
    RenderOptions rgb;
    rgb.rgbMode = true;
    Film film(8, 8);
    SpectralFilm spectral(8, 8, SpectralBins(10.0));
    EXPECT_THROW(Renderer(scene, rgb).render(film, nullptr, &spectral), Error);
    SpectralFilm small(4, 8, SpectralBins(10.0));
    EXPECT_THROW(Renderer(scene, RenderOptions{}).render(film, nullptr, &small), Error);
    EXPECT_THROW(SpectralFilm(100000, 100000, SpectralBins(1.0)), Error);
}

TEST(SpectralFilm, ImageRoundTripsThroughTheSpectralLayoutBitForBit) {
    SpectralFilm film(1, 1, SpectralBins(10.0));
    feed(film, [](float l) { return l / 550.0f; }, 500, 4);
    const Image img = film.image();
    const std::string path = iris::testing::tempPath("iris_spectral", "roundtrip.exr");
    writeEXR(path, img, spectralLayoutMetadata());
    const SpectralImage back = spectralChannels(readImage(path), path);
    ASSERT_EQ(back.bins(), 47);
    for (int b = 0; b < 47; ++b) {
        EXPECT_EQ(back.wavelengths[size_t(b)], 365.0 + 10.0 * b);
        EXPECT_EQ(back.values[size_t(b)], img.pixels[size_t(b)]);
    }
    EXPECT_EQ(metadataValue(readEXRMetadata(path), "spectralLayoutVersion"), "1.0");
    std::filesystem::remove(path);
}
