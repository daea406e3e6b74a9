// Film and pixel filter: filter importance sampling reproduces the truncated Gaussian and the box,
// the film's mean and counts are exact, and invalid estimates never reach a pixel.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "render/film.h"
#include "core/registry.h"
#include "render/renderer.h"
#include "core/rng.h"
#include "render/scene.h"
#include "tests/support/render_test_scenes.h"

using namespace iris;

TEST(PixelFilter, GaussianSamplesMatchTruncatedGaussian) {
    const ReconstructionFilterPtr gaussian = makeFilter("gaussian");  // stddev 0.5 px
    const ReconstructionFilter& filter = *gaussian;
    // Chi-square of 100k x-offsets in 30 bins over [−1.5, 1.5] against the truncated Gaussian.
    const int bins = 30, n = 100000;
    std::vector<double> counts(bins, 0.0);
    Pcg32 rng(3, 5);
    for (int i = 0; i < n; ++i) {
        const FilterSample fs = filter.sample(vec2(rng.uniform(), rng.uniform()));
        ASSERT_EQ(fs.weight, 1.0f);
        const vec2 o = fs.offset;
        ASSERT_LE(std::abs(o.x), 1.5f + 1e-6f);
        counts[std::clamp(int((o.x + 1.5f) / 3.0f * bins), 0, bins - 1)] += 1;
    }
    const double s = 0.5 * std::sqrt(2.0), norm = std::erf(1.5 / s);
    double chi2 = 0;
    for (int b = 0; b < bins; ++b) {
        const double x0 = -1.5 + 3.0 * b / bins, x1 = x0 + 3.0 / bins;
        const double p = (std::erf(x1 / s) - std::erf(x0 / s)) / (2 * norm);
        chi2 += sqr(counts[b] - p * n) / (p * n);
    }
    EXPECT_LT(chi2, 75.0);  // 29 degrees of freedom: 1e-5 upper quantile ≈ 70–75
}

TEST(PixelFilter, BoxSamplesAreUniform) {
    const ReconstructionFilterPtr filter = makeFilter("box");  // radius 0.5 px
    EXPECT_EQ(filter->sample(vec2(0.0f)).offset, vec2(-0.5f));
    EXPECT_EQ(filter->sample(vec2(0.5f)).offset, vec2(0.0f));
    Properties bad("rfilter", "box", SourceLocation{"f.xml", 3});
    bad.set("radius", -1.0f, SourceLocation{"f.xml", 4});
    EXPECT_THROW(RFilterRegistry::instance().create(bad), Error);
}

TEST(Film, VarianceInAnotherColourSpaceUsesTheCrossChannelMoments) {
    // Samples (1, 0, 0) and (0, 1, 0): per channel the variance of the mean is 1/4 in each of R and G,
    // but their sum R + G is constant, so in the space (R + G, R − G, B) it is 0 and 1.
    Film film(1, 1), plain(1, 1);
    mat3 m(0.0f);
    m[0] = vec3(1, 1, 0);   // column 0: the image of R
    m[1] = vec3(1, -1, 0);  // column 1: the image of G
    m[2] = vec3(0, 0, 1);
    film.setMomentSpace(m);
    for (Film* f : {&film, &plain}) {
        f->addSample(0, 0, vec3(1, 0, 0));
        f->addSample(0, 0, vec3(0, 1, 0));
    }
    EXPECT_EQ(film.pixel(0, 0), plain.pixel(0, 0));  // the mean stays in the film's space
    const std::vector<float> v = film.varianceOfMeanImage(), p = plain.varianceOfMeanImage();
    EXPECT_NEAR(v[0], 0.0f, 1e-7f);
    EXPECT_FLOAT_EQ(v[1], 1.0f);
    EXPECT_FLOAT_EQ(p[0], 0.25f);  // a per-channel transform of the RGB variances would give 0.5
    EXPECT_FLOAT_EQ(p[1], 0.25f);
}

TEST(Film, MeanAndCounts) {
    Film film(3, 2);
    film.addSample(1, 1, vec3(1, 2, 3));
    film.addSample(1, 1, vec3(3, 2, 1));
    EXPECT_EQ(film.pixel(1, 1), vec3(2, 2, 2));
    EXPECT_EQ(film.sampleCount(1, 1), 2u);
    EXPECT_EQ(film.pixel(0, 0), vec3(0.0f));
    // Sample variance of {1, 3} is 2; variance of the mean over 2 samples is 1.
    EXPECT_FLOAT_EQ(film.varianceOfMeanImage()[3 * (1 * 3 + 1)], 1.0f);
    EXPECT_FLOAT_EQ(film.varianceOfMeanImage()[3 * (1 * 3 + 1) + 1], 0.0f);
    EXPECT_EQ(film.minSampleCount(), 0u);
    EXPECT_EQ(film.totalSamples(), 2u);
    EXPECT_THROW(Film(0, 5), Error);
    EXPECT_THROW(Film(40000, 40000), Error);  // 1.6·10⁹ pixels: refused, not allocated
}

namespace {
// A test-only material whose BSDF returns NaN: the renderer must count and drop such samples.
class NaNBSDF final : public BSDF {
public:
    explicit NaNBSDF(int n) : n_(n) {}
    SampledSpectrum eval(const vec3&, const vec3&, TransportMode) const override {
        return SampledSpectrum(n_, std::numeric_limits<float>::quiet_NaN());
    }
    std::optional<BSDFSample> sample(const vec3&, float, const vec2&, TransportMode) const override { return std::nullopt; }
    float pdf(const vec3&, const vec3&, TransportMode) const override { return 0.0f; }
    uint32_t flags() const override { return kBSDFReflection | kBSDFDiffuse; }

private:
    int n_;
};
class NaNMaterial final : public Material {
public:
    const BSDF* getBSDF(const ShadingPoint&, SampledWavelengths& wl, Arena& arena) const override {
        return arena.make<NaNBSDF>(wl.size());
    }
};
}  // namespace

TEST(Film, InvalidSamplesAreCountedAndDropped) {
    SceneDescription d = iris::testing::furnaceScene(0.5f, 8, 4);
    d.shapes[0].material = std::make_shared<NaNMaterial>();
    const Scene scene(std::move(d));
    Film film(8, 8);
    RenderOptions opt;
    const RenderStats st = Renderer(scene, opt).render(film);
    EXPECT_GT(st.invalidSamples, 0u);
    for (float v : film.meanImage()) EXPECT_TRUE(std::isfinite(v));
    EXPECT_EQ(st.sppMin, 4u);
}

TEST(Film, FixedPointConversionIsExactOnBothSidesOfTheInt64FastPath) {
    // toFixed converts through int64_t below 2^63 (sample values below 2^15) and through the
    // 128-bit conversion above; both must give the integer nearest to v · 2^48 exactly.
    for (const float v : {0.0f, 1.0f, -1.0f, 0.1f, 3.3e-15f, 32767.998f, 32768.0f, 32768.004f, -32768.0f, -40000.5f,
                          1e9f, -1e9f, 0x1p47f, -0x1p47f, 1e30f}) {
        const double d = std::clamp(double(v), -Film::kMaxSampleValue, Film::kMaxSampleValue) * 0x1p48;
        const Film::FixedSum expect = Film::FixedSum(std::nearbyint(d));  // the generic conversion
        EXPECT_TRUE(Film::toFixed(v) == expect) << v;
        // Independent check of the value: the sum of the parts recovers d exactly.
        EXPECT_EQ(double(Film::toFixed(v)), std::nearbyint(d)) << v;
    }
}
