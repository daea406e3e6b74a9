// Renderer tests: the white furnace converges to the analytic value in both modes, images are
// bit-identical for any thread count, and a resumed render equals an uninterrupted one.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdio>

#include "render/film.h"
#include "render/renderer.h"
#include "render/scene.h"
#include "tests/support/render_test_scenes.h"

using namespace iris;
using namespace iris::testing;

namespace {

struct PixelStats {
    double mean = 0, stderr_ = 0;
    int count = 0;
};

/// Mean and standard error of one channel over the pixels whose centre ray hits the sphere
/// (pixel means are independent estimates of the same value).
PixelStats sphereStats(const Film& film, int channel, float maxRadiusFraction) {
    const int w = film.width(), h = film.height();
    double s = 0, s2 = 0;
    int n = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const float dx = (x + 0.5f) / w - 0.5f, dy = (y + 0.5f) / h - 0.5f;
            if (std::sqrt(dx * dx + dy * dy) > maxRadiusFraction) continue;
            const double v = film.pixel(x, y)[channel];
            s += v;
            s2 += v * v;
            ++n;
        }
    PixelStats st;
    st.count = n;
    st.mean = s / n;
    const double var = std::max(0.0, s2 / n - st.mean * st.mean);
    st.stderr_ = std::sqrt(var / n);
    return st;
}

Film renderFilm(const Scene& scene, RenderOptions opt) {
    Film film(scene.description().camera.width, scene.description().camera.height);
    Renderer(scene, opt).render(film);
    return film;
}

}  // namespace

TEST(Render, FurnaceDiffuseSphereRgbMode) {
    // A convex diffuse object of albedo ρ under uniform radiance 1 reflects exactly ρ.
    const Scene scene(furnaceScene(0.5f, 24, 64));
    RenderOptions opt;
    opt.rgbMode = true;
    opt.seed = 1;
    const Film film = renderFilm(scene, opt);
    // The sphere's silhouette has radius tan(asin(1/4))/tan(20°) = 0.71 of the half-frame, i.e.
    // 0.355 image widths: the central disk of radius 0.3 is entirely sphere, the corners are not.
    for (int c = 0; c < 3; ++c) {
        const PixelStats st = sphereStats(film, c, 0.3f);
        ASSERT_GT(st.count, 50);
        EXPECT_NEAR(st.mean, 0.5, 5 * st.stderr_ + 1e-6) << "channel " << c;
    }
    // Background pixels (corners) see the environment directly: exactly 1.
    EXPECT_FLOAT_EQ(film.pixel(0, 0).x, 1.0f);
}

TEST(Render, FurnaceDiffuseSphereSpectralMode) {
    const Scene scene(furnaceScene(0.5f, 24, 64));
    for (int n : {1, 4, 16}) {
        RenderOptions opt;
        opt.rgbMode = false;
        opt.spectralSamples = n;
        opt.seed = 2;
        const Film film = renderFilm(scene, opt);
        // Film holds XYZ; a constant spectrum ρ under illuminant E has Y = ρ (docs/conventions.md).
        const PixelStats st = sphereStats(film, 1, 0.3f);
        EXPECT_NEAR(st.mean, 0.5, 5 * st.stderr_ + 1e-6) << "N = " << n;
    }
}

TEST(Render, IdenticalForAnyThreadCount) {
    const Scene scene(furnaceScene(0.7f, 20, 4));
    RenderOptions opt;
    opt.spectralSamples = 8;
    opt.seed = 11;
    opt.threads = 1;
    const Film a = renderFilm(scene, opt);
    opt.threads = 2;
    const Film b = renderFilm(scene, opt);
    opt.threads = 5;
    const Film c = renderFilm(scene, opt);
    EXPECT_EQ(a.meanImage(), b.meanImage());
    EXPECT_EQ(a.meanImage(), c.meanImage());
    // A different seed changes the image (the test can fail).
    opt.seed = 12;
    EXPECT_NE(a.meanImage(), renderFilm(scene, opt).meanImage());
}

TEST(Render, ResumeFromCheckpointIsBitExact) {
    const Scene scene(furnaceScene(0.6f, 16, 8));
    const std::string ckpt = ::testing::TempDir() + "iris_resume_test.ckpt";
    RenderOptions opt;
    opt.seed = 5;
    opt.spp = 8;
    const Film full = renderFilm(scene, opt);

    RenderOptions first = opt;
    first.spp = 3;
    first.checkpointPath = ckpt;
    renderFilm(scene, first);

    RenderOptions second = opt;
    second.checkpointPath = ckpt;
    second.resume = true;
    Film resumed(16, 16);
    const Renderer r(scene, second);
    resumed.load(ckpt, r.settingsKey());
    EXPECT_EQ(resumed.minSampleCount(), 3u);
    r.render(resumed);
    EXPECT_EQ(resumed.minSampleCount(), 8u);
    EXPECT_EQ(full.meanImage(), resumed.meanImage());

    // A checkpoint from other settings is refused.
    RenderOptions other = opt;
    other.seed = 6;
    Film f(16, 16);
    EXPECT_THROW(f.load(ckpt, Renderer(scene, other).settingsKey()), Error);
    std::remove(ckpt.c_str());
}

TEST(Render, CancellationKeepsCompletedSamples) {
    const Scene scene(furnaceScene(0.5f, 16, 1000000));
    RenderOptions opt;
    std::atomic<bool> cancel{true};  // cancelled before the first pass
    Film film(16, 16);
    const RenderStats st = Renderer(scene, opt).render(film, &cancel);
    EXPECT_TRUE(st.interrupted);
    EXPECT_EQ(st.sppMin, 0u);

    // Time limit: stops by itself, keeps whole passes.
    RenderOptions timed;
    timed.timeLimit = 0.3;
    Film film2(16, 16);
    const RenderStats st2 = Renderer(scene, timed).render(film2);
    EXPECT_TRUE(st2.timeLimited);
    EXPECT_GT(st2.sppMin, 0u);
    EXPECT_LT(st2.sppMin, 1000000u);
}

TEST(Render, InvalidOptionsAreErrors) {
    const Scene scene(furnaceScene(0.5f, 8, 4));
    RenderOptions opt;
    opt.spectralSamples = 0;
    EXPECT_THROW(Renderer(scene, opt), Error);
    opt.spectralSamples = 33;
    EXPECT_THROW(Renderer(scene, opt), Error);
    RenderOptions o2;
    o2.spp = 0;
    EXPECT_THROW(Renderer(scene, o2), Error);
    EXPECT_THROW(Film(100000, 100000), Error);
}
