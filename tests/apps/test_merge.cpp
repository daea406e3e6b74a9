// Merging renders: sample-count-weighted mean, the expected variance reduction on synthetic noise,
// metadata bookkeeping and refusal of incompatible inputs; plus the file round trip.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>

#include "core/error.h"
#include "core/rng.h"
#include "metrics/merge_renders.h"

using namespace iris;

namespace {

double gaussian(Pcg32& rng) {
    // Box–Muller transform.
    const double u1 = 1.0 - rng.uniformDouble(), u2 = rng.uniformDouble();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * 3.14159265358979323846 * u2);
}

ImageMetadata renderMeta(int spp, int seed) {
    return {{"iris.spp", std::to_string(spp)},     {"iris.seed", std::to_string(seed)},
            {"iris.mode", "spectral"},             {"iris.spectral_samples", "4"},
            {"iris.render_time_s", "1.5"},         {"iris.rays", "1000"},
            {"iris.scene", "scenes/test.xml"},     {"iris.version", "0.1.0"}};
}

/// A synthetic render with `spp` samples: per-value mean μ (a fixed gradient) plus Gaussian noise of
/// variance σ²/spp, as a Monte Carlo estimate with per-sample variance σ² would have.
RenderFile syntheticRender(int w, int h, int spp, int seed, double sigma2) {
    Pcg32 rng(uint64_t(seed), 77);
    Image img(w, h, 3);
    for (size_t i = 0; i < img.pixels.size(); ++i)
        img.pixels[i] = float(0.1 + 0.8 * double(i % 97) / 97.0 + std::sqrt(sigma2 / spp) * gaussian(rng));
    return RenderFile{"render_" + std::to_string(seed) + ".exr", img, renderMeta(spp, seed)};
}

template <typename Fn>
void expectErrorContaining(Fn fn, const std::string& a, const std::string& b) {
    try {
        fn();
        ADD_FAILURE() << "no error";
    } catch (const Error& e) {
        const std::string msg = e.what();
        EXPECT_NE(msg.find(a), std::string::npos) << msg;
        EXPECT_NE(msg.find(b), std::string::npos) << msg;
    }
}

}  // namespace

TEST(Merge, WeightedMeanBySampleCount) {
    RenderFile a{"a.exr", Image(1, 1, 3), renderMeta(1, 1)}, b{"b.exr", Image(1, 1, 3), renderMeta(3, 2)};
    a.image.pixels = {1.0f, 0.0f, 8.0f};
    b.image.pixels = {0.0f, 4.0f, 0.0f};
    const RenderFile m = mergeRenders({a, b});
    EXPECT_FLOAT_EQ(m.image.pixels[0], 0.25f);
    EXPECT_FLOAT_EQ(m.image.pixels[1], 3.0f);
    EXPECT_FLOAT_EQ(m.image.pixels[2], 2.0f);
    EXPECT_EQ(metadataValue(m.meta, "iris.spp"), "4");
    EXPECT_EQ(metadataValue(m.meta, "iris.seed"), "1,2");
    EXPECT_EQ(metadataValue(m.meta, "iris.merged_from"), "2");
    EXPECT_EQ(metadataValue(m.meta, "iris.render_time_s"), "3");
    EXPECT_EQ(metadataValue(m.meta, "iris.rays"), "2000");
    EXPECT_EQ(metadataValue(m.meta, "iris.mode"), "spectral");
    EXPECT_EQ(metadataValue(m.meta, "iris.scene"), "scenes/test.xml");
}

TEST(Merge, VarianceReductionMatchesSummedSampleCount) {
    // k = 4 renders with spp 1, 2, 4, 9: the merge must have per-value error variance σ²/16 and be
    // unbiased. Over P values, the error variance estimate has relative standard error sqrt(2/P)
    // and the mean error has standard error sqrt(σ²/16/P); allow 4 standard errors.
    const int w = 64, h = 64;
    const double sigma2 = 0.5;
    const int spps[4] = {1, 2, 4, 9};
    std::vector<RenderFile> inputs;
    for (int i = 0; i < 4; ++i) inputs.push_back(syntheticRender(w, h, spps[i], 100 + i, sigma2));
    const RenderFile m = mergeRenders(inputs);
    const double P = 3.0 * w * h;
    double sumErr = 0, sumErr2 = 0, sumErrFirst2 = 0;
    for (size_t i = 0; i < m.image.pixels.size(); ++i) {
        const double mu = 0.1 + 0.8 * double(i % 97) / 97.0;
        const double e = m.image.pixels[i] - mu;
        sumErr += e;
        sumErr2 += e * e;
        sumErrFirst2 += (inputs[0].image.pixels[i] - mu) * (inputs[0].image.pixels[i] - mu);
    }
    const double expectedVar = sigma2 / 16.0;
    EXPECT_NEAR(sumErr / P, 0.0, 4 * std::sqrt(expectedVar / P));
    EXPECT_NEAR(sumErr2 / P, expectedVar, 4 * expectedVar * std::sqrt(2.0 / P));
    // Reduction relative to the 1-spp render: 16x in variance.
    EXPECT_NEAR((sumErrFirst2 / P) / (sumErr2 / P), 16.0, 16.0 * 8 * std::sqrt(2.0 / P));
    EXPECT_EQ(metadataValue(m.meta, "iris.spp"), "16");
}

TEST(Merge, EqualWeightsWouldBeWorse) {
    // Sanity check of the test itself: an unweighted mean of the same inputs has larger variance
    // (Σ σ²/n_i / k² = σ²·(1 + 1/2 + 1/4 + 1/9)/16 > σ²/16), so the weighted result is distinguishable.
    const double sigma2 = 0.5;
    const double unweighted = sigma2 * (1.0 + 0.5 + 0.25 + 1.0 / 9.0) / 16.0, weighted = sigma2 / 16.0;
    const double P = 3.0 * 64 * 64;
    EXPECT_GT(unweighted - weighted, 8 * weighted * std::sqrt(2.0 / P));
}

TEST(Merge, RefusesIncompatibleInputs) {
    const RenderFile a = syntheticRender(4, 4, 2, 1, 0.1);
    RenderFile b = syntheticRender(4, 4, 2, 2, 0.1);
    RenderFile small = syntheticRender(4, 3, 2, 3, 0.1);
    small.path = "small.exr";
    expectErrorContaining([&] { mergeRenders({a, small}); }, "small.exr", "differ");

    RenderFile rgb = b;
    rgb.path = "rgb.exr";
    for (auto& [k, v] : rgb.meta)
        if (k == "iris.mode") v = "rgb";
    expectErrorContaining([&] { mergeRenders({a, rgb}); }, "rgb.exr", "iris.mode");

    RenderFile otherScene = b;
    otherScene.path = "other.exr";
    for (auto& [k, v] : otherScene.meta)
        if (k == "iris.scene") v = "scenes/other.xml";
    expectErrorContaining([&] { mergeRenders({a, otherScene}); }, "other.exr", "iris.scene");

    RenderFile sameSeed = syntheticRender(4, 4, 2, 1, 0.1);
    sameSeed.path = "same.exr";
    expectErrorContaining([&] { mergeRenders({a, sameSeed}); }, "same.exr", "seed");

    RenderFile noSpp = b;
    noSpp.path = "nospp.exr";
    noSpp.meta.erase(noSpp.meta.begin());
    expectErrorContaining([&] { mergeRenders({a, noSpp}); }, "nospp.exr", "iris.spp");

    RenderFile badSpp = b;
    badSpp.path = "bad.exr";
    badSpp.meta[0].second = "12x";
    expectErrorContaining([&] { mergeRenders({a, badSpp}); }, "bad.exr", "iris.spp");

    EXPECT_THROW(mergeRenders({}), Error);
}

TEST(Merge, FilesRoundTrip) {
    namespace fs = std::filesystem;
    const fs::path dir = fs::temp_directory_path() / ("iris_test_merge_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    std::vector<std::string> paths;
    for (int i = 0; i < 3; ++i) {
        const RenderFile r = syntheticRender(8, 5, 4, 10 + i, 0.2);
        paths.push_back((dir / ("r" + std::to_string(i) + ".exr")).string());
        writeEXR(paths.back(), r.image, r.meta);
    }
    const RenderFile m = mergeRenderFiles(paths);
    EXPECT_EQ(metadataValue(m.meta, "iris.spp"), "12");
    EXPECT_EQ(metadataValue(m.meta, "iris.seed"), "10,11,12");
    const Image a = readImage(paths[0]), b = readImage(paths[1]), c = readImage(paths[2]);
    EXPECT_NEAR(m.image.at(3, 2, 1), (a.at(3, 2, 1) + b.at(3, 2, 1) + c.at(3, 2, 1)) / 3.0f, 1e-6f);
    fs::remove_all(dir);
}
