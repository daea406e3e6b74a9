// Regression renders: small images of the thesis' parameter sets (RGB mode) and of key spectral
// scenes are compared with committed references (tests/data/regression/*.exr). Each reference
// stores the per-pixel mean and the variance of that mean; the test renders the same scene with
// another seed and fewer samples and compares 4×4-pixel block means with z-scores built from both
// images' variances. A change to any model shifts the means by many standard errors and fails; a
// change that only alters the noise (seeds, sampling order) does not.
//
// Regenerate the references after an intended change with
//   IRIS_REGENERATE_REFERENCES=1 build/iris_tests --gtest_filter='RegressionRenders*'
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include "render/film.h"
#include "core/io/image.h"
#include "core/source_tree.h"
#include "render/loader/scene_loader.h"
#include "render/renderer.h"
#include "render/scene.h"

using namespace iris;

namespace {

struct RegressionCase {
    const char* name;
    const char* scene;  // relative to the repository
    bool rgbMode;
    int spectralSamples;
    std::map<std::string, std::string> defines;
};

const char* kCloseup = "tests/data/regression/scenes/closeup.xml";

const std::vector<RegressionCase>& cases() {
    static const std::vector<RegressionCase> c = {
        {"granier_table31_rgb", kCloseup, true, 3, {{"material", "granier_table31"}}},
        {"granier_table31_spectral", kCloseup, false, 8, {{"material", "granier_table31"}}},
        {"proposed_table42_rgb", kCloseup, true, 3, {{"material", "proposed_table42"}}},
        {"proposed_table42_spectral", kCloseup, false, 8, {{"material", "proposed_table42"}}},
        {"proposed_table43_rgb", kCloseup, true, 3, {{"material", "proposed_table43"}}},
        {"thinfilm_gold_rgb", kCloseup, true, 3, {{"material", "thinfilm_gold"}}},
        {"thinfilm_gold_spectral", kCloseup, false, 8, {{"material", "thinfilm_gold"}}},
        {"iridescent_diffuse_spectral", kCloseup, false, 8, {{"material", "iridescent_diffuse"}}},
        {"thesis_comparison_table43_rgb", "scenes/thesis_comparison_table43.xml", true, 3, {}},
        {"default_spectral", "scenes/default.xml", false, 4, {}},
    };
    return c;
}

constexpr int kRes = 64, kRefSpp = 512, kTestSpp = 48, kBlock = 4;

std::string repoPath(const std::string& rel) { return sourcePath(rel); }
std::string referencePath(const RegressionCase& c) { return repoPath("tests/data/regression/" + std::string(c.name) + ".exr"); }

/// Render a case; returns a 6-channel image: film mean (3) and variance of the mean (3).
Image render(const RegressionCase& c, int spp, uint64_t seed, std::map<std::string, std::string> extraDefines = {}) {
    std::map<std::string, std::string> defines = c.defines;
    defines["res"] = std::to_string(kRes);
    for (const auto& [k, v] : extraDefines) defines[k] = v;
    const Scene scene(loadScene(repoPath(c.scene), defines));
    RenderOptions opt;
    opt.rgbMode = c.rgbMode;
    opt.spectralSamples = c.spectralSamples;
    opt.spp = spp;
    opt.seed = seed;
    Film film(scene.description().camera.width, scene.description().camera.height);
    Renderer(scene, opt).render(film);
    Image img(film.width(), film.height(), 6);
    img.channelNames = {"R", "G", "B", "var.R", "var.G", "var.B"};
    const std::vector<float> mean = film.meanImage(), var = film.varianceOfMeanImage();
    for (size_t p = 0; p < img.pixelCount(); ++p)
        for (int ch = 0; ch < 3; ++ch) {
            img.pixels[6 * p + ch] = mean[3 * p + ch];
            img.pixels[6 * p + 3 + ch] = var[3 * p + ch];
        }
    return img;
}

struct Comparison {
    double meanZ2 = 0;           // 4×4 blocks: mean of z² over blocks and channels (≈ 1 when equal)
    double fractionOver4 = 0;    // 4×4 blocks: fraction of |z| > 4
    double maxAbsZ = 0;          // 4×4 blocks: largest |z|
    double maxRegionZ = 0;       // 16×16 regions and the whole image: largest |z| (systematic shifts)
};

/// z-score of the difference of the mean over a rectangle: the variances of the pixel means add.
double regionZ(const Image& test, const Image& ref, int x0, int y0, int size, int ch) {
    double mt = 0, mr = 0, v = 0;
    for (int y = y0; y < y0 + size; ++y)
        for (int x = x0; x < x0 + size; ++x) {
            mt += test.at(x, y, ch);
            mr += ref.at(x, y, ch);
            v += test.at(x, y, 3 + ch) + ref.at(x, y, 3 + ch);
        }
    // A floor for regions whose samples are all identical (e.g. pure background).
    return (mt - mr) / std::sqrt(v + 1e-12 + 1e-10 * mr * mr);
}

Comparison compareBlocks(const Image& test, const Image& ref) {
    Comparison c;
    int n = 0, over = 0;
    for (int by = 0; by + kBlock <= test.height; by += kBlock)
        for (int bx = 0; bx + kBlock <= test.width; bx += kBlock)
            for (int ch = 0; ch < 3; ++ch) {
                const double z = regionZ(test, ref, bx, by, kBlock, ch);
                c.meanZ2 += z * z;
                c.maxAbsZ = std::max(c.maxAbsZ, std::abs(z));
                over += std::abs(z) > 4;
                ++n;
            }
    c.meanZ2 /= n;
    c.fractionOver4 = double(over) / n;
    for (int ch = 0; ch < 3; ++ch) {
        c.maxRegionZ = std::max(c.maxRegionZ, std::abs(regionZ(test, ref, 0, 0, test.width, ch)));
        for (int by = 0; by + 16 <= test.height; by += 16)
            for (int bx = 0; bx + 16 <= test.width; bx += 16)
                c.maxRegionZ = std::max(c.maxRegionZ, std::abs(regionZ(test, ref, bx, by, 16, ch)));
    }
    return c;
}

class RegressionRenders : public ::testing::TestWithParam<RegressionCase> {};

}  // namespace

namespace {
// Readable parameter names in test failures.
[[maybe_unused]] void PrintTo(const RegressionCase& c, std::ostream* os) { *os << c.name; }

}  // namespace

TEST_P(RegressionRenders, MatchesReferenceWithinNoise) {
    const RegressionCase& c = GetParam();
    if (std::getenv("IRIS_REGENERATE_REFERENCES")) {
        const Image ref = render(c, kRefSpp, 1000);
        writeEXR(referencePath(c), ref, {{"iris.regression.spp", std::to_string(kRefSpp)}, {"iris.scene", c.scene}});
        GTEST_SKIP() << "reference written: " << referencePath(c);
    }
    ASSERT_TRUE(std::filesystem::exists(referencePath(c))) << "missing reference; see the comment at the top of this file";
    const Image ref = readImage(referencePath(c));
    ASSERT_EQ(ref.channels, 6);
    const Image test = render(c, kTestSpp, 7);
    ASSERT_EQ(test.width, ref.width);
    const Comparison cmp = compareBlocks(test, ref);
    RecordProperty("mean_z2", std::to_string(cmp.meanZ2));
    std::printf("[ regression ] %s: mean z^2 = %.3f, |z|>4 in %.4f of blocks, max |z| = %.2f, max region |z| = %.2f\n",
                c.name, cmp.meanZ2, cmp.fractionOver4, cmp.maxAbsZ, cmp.maxRegionZ);
    // Equal expectations give mean z² ≈ 1 (a little above: variances are estimated from few
    // samples and fireflies make tails heavier than Gaussian).
    EXPECT_LT(cmp.meanZ2, 2.5);
    EXPECT_LT(cmp.fractionOver4, 0.02);
    // 51 regions (48 of 16×16 pixels, 3 whole-image channels): |z| > 5 has probability ~3e-5.
    EXPECT_LT(cmp.maxRegionZ, 5.0);
}

INSTANTIATE_TEST_SUITE_P(Scenes, RegressionRenders, ::testing::ValuesIn(cases()),
                         [](const ::testing::TestParamInfo<RegressionCase>& info) { return std::string(info.param.name); });

TEST(RegressionRendersSensitivity, ModelChangesAreDetected) {
    // Granier Table 3.1 with ws 0.5 → 0.55, and with d 76 → 80 nm: both comparisons must fail.
    const RegressionCase& c = cases()[0];
    ASSERT_TRUE(std::filesystem::exists(referencePath(c)));
    const Image ref = readImage(referencePath(c));
    for (const char* variant : {"granier_table31_ws055", "granier_table31_d80"}) {
        const Image changed = render(c, kTestSpp, 7, {{"material", variant}});
        const Comparison cmp = compareBlocks(changed, ref);
        std::printf("[ regression ] %s vs %s: mean z^2 = %.3f, |z|>4 in %.4f of blocks, max region |z| = %.2f\n", variant,
                    c.name, cmp.meanZ2, cmp.fractionOver4, cmp.maxRegionZ);
        EXPECT_TRUE(cmp.meanZ2 > 2.5 || cmp.fractionOver4 > 0.02 || cmp.maxRegionZ > 5.0) << variant;
    }
}
