// The splat film of light-tracing renders (render/splat_film.h): exact, order- and thread-
// independent sums (the 128-bit fixed point from two 64-bit atomics, carries included), the
// reconstruction filter's normalised weights, and the refusal of invalid values.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <thread>

#include "render/splat_film.h"

using namespace iris;

namespace {

struct Splat {
    vec2 pos;
    float value;
};

std::vector<Splat> randomSplats(int n, int w, int h) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::vector<Splat> s(static_cast<size_t>(n));
    for (Splat& x : s) {
        x.pos = vec2(u(rng) * float(w), u(rng) * float(h));
        // Magnitudes from 1e-6 to 1e12: sums whose low words wrap many times.
        x.value = std::pow(10.0f, -6.0f + 18.0f * u(rng));
    }
    return s;
}

Film flushed(SplatFilm& s) {
    Film f(s.width(), s.height());
    s.flushInto(f);
    return f;
}

TEST(SplatFilm, SumsAreTheSameBitsForAnyOrderAndThreadCount) {
    const int w = 9, h = 7;
    const ReconstructionFilterPtr filter = makeFilter("mitchell");  // negative lobes: signed sums
    const std::vector<Splat> splats = randomSplats(20000, w, h);
    const SampledWavelengths wl = SampledWavelengths::rgb(defaultChannelWavelengths());
    auto add = [&](SplatFilm& f, const Splat& s) { f.splat(s.pos, SampledSpectrum(3, s.value), wl); };

    SplatFilm one(w, h, *filter, true);
    for (const Splat& s : splats) add(one, s);
    std::vector<Splat> shuffled = splats;
    std::shuffle(shuffled.begin(), shuffled.end(), std::mt19937(3));
    SplatFilm many(w, h, *filter, true);
    std::vector<std::thread> threads;
    for (int t = 0; t < 4; ++t)
        threads.emplace_back([&, t] {
            for (size_t i = size_t(t); i < shuffled.size(); i += 4) add(many, shuffled[i]);
        });
    for (std::thread& t : threads) t.join();
    const Film a = flushed(one), b = flushed(many);
    EXPECT_EQ(a.meanImage(), b.meanImage());
    // The sums carry: with a box filter (every splat inside the image) the total is what doubles
    // give, to their precision.
    const ReconstructionFilterPtr box = makeFilter("box");  // the film keeps a reference: it must outlive it
    SplatFilm boxed(w, h, *box, true);
    for (const Splat& s : splats) add(boxed, s);
    double total = 0, expected = 0;
    for (float v : flushed(boxed).meanImage()) total += v;
    for (const Splat& s : splats) expected += 3.0 * s.value / (w * h);
    EXPECT_NEAR(total / expected, 1.0, 1e-6);
    // A different set of splats gives a different image (the comparison can fail).
    SplatFilm other(w, h, *filter, true);
    for (size_t i = 1; i < splats.size(); ++i) add(other, splats[i]);
    EXPECT_NE(a.meanImage(), flushed(other).meanImage());
}

TEST(SplatFilm, FilterWeightsAreNormalised) {
    const int w = 12, h = 12;
    const SampledWavelengths wl = SampledWavelengths::rgb(defaultChannelWavelengths());
    // Box filter: a splat lands in the one pixel it falls in, scaled by 1/(w h).
    const ReconstructionFilterPtr box = makeFilter("box");
    SplatFilm b(w, h, *box, true);
    b.splat(vec2(3.3f, 2.7f), SampledSpectrum(3, 144.0f), wl);
    const Film fb = flushed(b);
    EXPECT_FLOAT_EQ(fb.pixel(3, 2).y, 1.0f);
    EXPECT_EQ(fb.pixel(4, 2).y, 0.0f);
    EXPECT_EQ(fb.sampleCount(0, 0), 1u);  // a flush is one sample of every pixel
    // Gaussian (and tent): over positions uniform in a pixel, the weights of all pixels average to
    // 1 (the filter integrates to 1), as filter importance sampling's camera samples do.
    for (const char* name : {"gaussian", "tent", "lanczos"}) {
        const ReconstructionFilterPtr f = makeFilter(name);
        SplatFilm g(w, h, *f, true);
        const int n = 64;
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) g.splat(vec2(6.0f + (i + 0.5f) / n, 5.0f + (j + 0.5f) / n), SampledSpectrum(3, 144.0f / (n * n)), wl);
        double sum = 0;
        const Film fg = flushed(g);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) sum += fg.pixel(x, y).y;
        EXPECT_NEAR(sum, 1.0, 2e-3) << name;
    }
}

TEST(SplatFilm, InvalidSplatsAreCountedAndDropped) {
    const ReconstructionFilterPtr box = makeFilter("box");
    const SampledWavelengths wl = SampledWavelengths::rgb(defaultChannelWavelengths());
    SplatFilm s(4, 4, *box, true);
    s.splat(vec2(1.5f), SampledSpectrum(3, NAN), wl);
    s.splat(vec2(1.5f), SampledSpectrum(3, -1.0f), wl);
    s.splat(vec2(1.5f), SampledSpectrum(3, INFINITY), wl);
    s.splat(vec2(-50.0f), SampledSpectrum(3, 1.0f), wl);  // far outside: nothing, and not invalid
    EXPECT_EQ(s.invalidSplats(), 3u);
    const Film f = flushed(s);
    EXPECT_EQ(f.pixel(1, 1), vec3(0.0f));
}

}  // namespace
