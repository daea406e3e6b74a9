// Piecewise-constant distributions (core/sampling.h): the guide-table CDF inversion returns
// exactly the interval of the plain binary search, and the tabulated 2D density equals the one
// computed from the conditional and marginal distributions; sampled histograms match the pdf.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "core/rng.h"
#include "core/sampling.h"

using namespace iris;

namespace {

std::vector<std::vector<float>> testFunctions() {
    std::vector<std::vector<float>> fs;
    fs.push_back({1.0f});
    fs.push_back({0.0f, 0.0f, 0.0f});  // all zero: uniform CDF
    fs.push_back(std::vector<float>(64, 1.0f));
    Pcg32 rng(11, 5);
    std::vector<float> r(1000);
    for (float& v : r) v = rng.uniform();
    fs.push_back(r);
    // A bright spike over a dim background (like an environment map's sun), and runs of zeros.
    std::vector<float> spike(512, 1e-3f);
    spike[77] = 1e5f;
    spike[300] = 50.0f;
    for (int i = 400; i < 480; ++i) spike[i] = 0.0f;
    fs.push_back(spike);
    std::vector<float> steep(300);
    for (int i = 0; i < 300; ++i) steep[i] = std::exp(-0.1f * i);
    fs.push_back(steep);
    return fs;
}

}  // namespace

TEST(Distribution1D, GuideTableMatchesBinarySearch) {
    Pcg32 rng(3, 9);
    for (const auto& f : testFunctions()) {
        const Distribution1D d(f);
        std::vector<float> us = {0.0f, 1e-30f, 0.5f, kOneMinusEpsilon, 1.0f, 1.5f, -0.25f, std::nextafter(1.0f, 0.0f),
                                 std::numeric_limits<float>::quiet_NaN()};
        for (int i = 0; i < 20000; ++i) us.push_back(rng.uniform());
        // Exact bucket edges b/n and their float neighbours (where rounding of u·n matters).
        const int n = d.count();
        for (int b = 0; b <= n; ++b) {
            const float e = float(b) / float(n);
            us.push_back(e);
            us.push_back(std::nextafter(e, 0.0f));
            us.push_back(std::nextafter(e, 2.0f));
        }
        for (float u : us) {
            ASSERT_EQ(d.findInterval(u), d.findIntervalBinary(u)) << "u = " << u << ", n = " << n;
            float pdfA, pmf;
            int off;
            const float x = d.sampleContinuous(u, &pdfA, &off);
            if (u >= 0.0f && u < 1.0f) {
                EXPECT_GE(x, 0.0f);
                EXPECT_LT(x, 1.0f);
            }
            EXPECT_EQ(off, d.findIntervalBinary(u));
            EXPECT_EQ(d.sampleDiscrete(u, &pmf), d.findIntervalBinary(u));
        }
    }
}

TEST(Distribution1D, SampledHistogramMatchesPdf) {
    // Chi-square of 200k continuous samples in the distribution's own bins (fixed seed).
    std::vector<float> f(40);
    for (int i = 0; i < 40; ++i) f[i] = 0.2f + float((i * 7) % 11);
    const Distribution1D d(f);
    const int samples = 200000;
    std::vector<double> counts(40, 0.0);
    Pcg32 rng(21, 4);
    for (int i = 0; i < samples; ++i) {
        float pdf;
        const float x = d.sampleContinuous(rng.uniform(), &pdf);
        const int bin = std::min(39, int(x * 40));
        EXPECT_FLOAT_EQ(pdf, d.pdf(x));
        counts[bin] += 1;
    }
    double chi2 = 0, pdfIntegral = 0;
    for (int b = 0; b < 40; ++b) {
        const double expected = d.pdf((b + 0.5f) / 40) / 40.0 * samples;
        pdfIntegral += d.pdf((b + 0.5f) / 40) / 40.0;
        chi2 += sqr(counts[b] - expected) / expected;
    }
    EXPECT_NEAR(pdfIntegral, 1.0, 1e-5);
    EXPECT_LT(chi2, 100.0);  // 39 degrees of freedom: the 1e-6 upper quantile is about 97
}

TEST(Distribution2D, TabulatedPdfEqualsGeneral) {
    const int nu = 37, nv = 19;
    std::vector<float> f(nu * nv);
    Pcg32 rng(5, 1);
    for (float& v : f) v = rng.uniform() < 0.2f ? 0.0f : rng.uniform() * 10.0f;
    f[5 * nu + 3] = 1e4f;
    const Distribution2D d(f, nu, nv);
    // Texel centres, texel edges and random points, all exactly equal (same expression).
    for (int v = 0; v <= nv; ++v)
        for (int u = 0; u <= nu; ++u) {
            for (const vec2 p : {vec2((u + 0.5f) / nu, (v + 0.5f) / nv), vec2(float(u) / nu, float(v) / nv)})
                ASSERT_EQ(d.pdf(p), d.pdfGeneral(p)) << p.x << ", " << p.y;
        }
    double integral = 0;
    for (int v = 0; v < nv; ++v)
        for (int u = 0; u < nu; ++u) integral += d.pdf(vec2((u + 0.5f) / nu, (v + 0.5f) / nv)) / (nu * nv);
    EXPECT_NEAR(integral, 1.0, 1e-5);
    int mismatches = 0;
    const int n = 20000;
    for (int i = 0; i < n; ++i) {
        const vec2 u(rng.uniform(), rng.uniform());
        ASSERT_EQ(d.pdf(u), d.pdfGeneral(u));
        float pdf;
        const vec2 p = d.sampleContinuous(u, &pdf);
        // The sample's density agrees with pdf(), except where a sample within float rounding of
        // a texel edge is mapped back to the neighbouring texel.
        mismatches += !(std::abs(pdf - d.pdf(p)) <= 1e-4f * pdf + 1e-6f);
    }
    EXPECT_LE(mismatches, n / 500);
    const Distribution2D zero(std::vector<float>(nu * nv, 0.0f), nu, nv);
    EXPECT_EQ(zero.pdf(vec2(0.3f, 0.6f)), zero.pdfGeneral(vec2(0.3f, 0.6f)));
}
