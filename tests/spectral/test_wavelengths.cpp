// Wavelength sampling: the visible-importance pdf is normalised, matches a histogram of its
// sampler, and hero rotations are stratified.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/error.h"
#include "core/rng.h"
#include "spectral/wavelengths.h"

using namespace iris;

TEST(Wavelengths, VisiblePdfIntegratesToOne) {
    // Midpoint rule with 0.01 nm steps: error far below the tolerance for this smooth pdf.
    double integral = 0;
    const int n = 47000;
    const double h = (kLambdaMax - kLambdaMin) / n;
    for (int i = 0; i < n; ++i) integral += visibleWavelengthPdf(float(kLambdaMin + (i + 0.5) * h)) * h;
    EXPECT_NEAR(integral, 1.0, 1e-4);
    EXPECT_EQ(visibleWavelengthPdf(kLambdaMin - 1), 0.0f);
    EXPECT_EQ(visibleWavelengthPdf(kLambdaMax + 1), 0.0f);
}

TEST(Wavelengths, SamplerMatchesPdfHistogram) {
    // Chi-square test of 200k samples in 47 bins of 10 nm against the integrated pdf.
    const int bins = 47, samples = 200000;
    std::vector<double> counts(bins, 0.0);
    Pcg32 rng(7, 3);
    for (int i = 0; i < samples; ++i) {
        const float l = sampleVisibleWavelength(rng.uniform());
        ASSERT_GE(l, kLambdaMin);
        ASSERT_LE(l, kLambdaMax);
        counts[std::min(bins - 1, int((l - kLambdaMin) / 10.0f))] += 1;
    }
    double chi2 = 0;
    for (int b = 0; b < bins; ++b) {
        double p = 0;
        for (int k = 0; k < 100; ++k) p += visibleWavelengthPdf(kLambdaMin + 10.0f * b + 0.1f * (k + 0.5f)) * 0.1;
        const double expected = p * samples;
        chi2 += sqr(counts[b] - expected) / expected;
    }
    // 46 degrees of freedom: the 1e-6 upper quantile is about 110.
    EXPECT_LT(chi2, 110.0);
}

TEST(Wavelengths, HeroRotationsAreStratified) {
    for (int n : {1, 2, 4, 8, 16, 32}) {
        const SampledWavelengths wl = SampledWavelengths::sampleVisible(0.3f, n);
        ASSERT_EQ(wl.size(), n);
        EXPECT_FALSE(wl.isRGB());
        for (int i = 0; i < n; ++i) {
            EXPECT_GT(wl.pdf(i), 0.0f);
            // The pdf comes from the sample's tanh value, not from the rounded λ (see below).
            EXPECT_NEAR(wl.pdf(i), visibleWavelengthPdf(wl.lambda(i)), 2e-6f * wl.pdf(i));
        }
        // The primary samples (0.3 + i/n) mod 1 each fall in a different 1/n stratum.
        std::vector<int> strata(n, 0);
        for (int i = 0; i < n; ++i) {
            float u = 0.3f + float(i) / n;
            if (u >= 1) u -= 1;
            strata[std::min(n - 1, int(u * n))]++;
        }
        for (int s : strata) EXPECT_EQ(s, 1);
    }
    EXPECT_THROW(SampledWavelengths::sampleVisible(0.5f, 0), std::exception);
    EXPECT_THROW(SampledWavelengths::sampleVisible(0.5f, kMaxWavelengths + 1), std::exception);
}

TEST(Wavelengths, TerminateSecondaryKeepsEstimatorUnbiased) {
    SampledWavelengths wl = SampledWavelengths::sampleVisible(0.42f, 4);
    const float heroPdf = wl.pdf(0);
    wl.terminateSecondary();
    EXPECT_TRUE(wl.secondaryTerminated());
    EXPECT_FLOAT_EQ(wl.pdf(0), heroPdf / 4);
    for (int i = 1; i < 4; ++i) EXPECT_EQ(wl.pdf(i), 0.0f);
}

TEST(Wavelengths, DefaultChannelWavelengthsAreTheThesis) {
    // Thesis 000 Table 3.1: λ = 645, 525, 445 nm for R, G, B (the one definition, wavelengths.h).
    EXPECT_EQ(defaultChannelWavelengths(), vec3(645.0f, 525.0f, 445.0f));
}

TEST(Wavelengths, RgbModeUsesFixedChannels) {
    const SampledWavelengths wl = SampledWavelengths::rgb(defaultChannelWavelengths());
    EXPECT_TRUE(wl.isRGB());
    EXPECT_EQ(wl.size(), 3);
    EXPECT_EQ(wl.lambda(0), 645.0f);
    EXPECT_EQ(wl.lambda(2), 445.0f);
    EXPECT_EQ(wl.pdf(1), 1.0f);
}

TEST(Wavelengths, FastFormsMatchTheTanhDefinition) {
    // visibleWavelengthPdf uses 4e^{-2|x|}/(1+e^{-2|x|})² and the sampler ½ln((1+t)/(1−t)) in
    // double; compare with the defining forms 1/(norm·cosh²x) and atanh (pbrt-v4 §4.6.5).
    const double a = 0.0072, c = 538.0;
    const double norm = (std::tanh(a * (kLambdaMax - c)) - std::tanh(a * (kLambdaMin - c))) / a;
    for (double l = kLambdaMin; l <= kLambdaMax; l += 0.37) {
        const double ref = 1.0 / (norm * sqr(std::cosh(a * (float(l) - c))));
        EXPECT_NEAR(visibleWavelengthPdf(float(l)), ref, 1e-6 * ref);
    }
    Pcg32 rng(17, 2);
    for (int i = 0; i < 100000; ++i) {
        const float u = i < 3 ? float(i) * 0.5f : rng.uniform();
        const double t = std::tanh(a * (kLambdaMin - c)) + double(u) * a * norm;
        const double ref = std::clamp(c + std::atanh(t) / a, double(kLambdaMin), double(kLambdaMax));
        // The sampler forms t in float (as before): |dλ/dt| = 1/(a(1−t²)) ≤ 2.4e3 nm times the
        // rounding of t near 1 (1.2e-7) is 2.9e-4 nm, plus half an ulp of λ (3e-5 nm).
        EXPECT_NEAR(sampleVisibleWavelength(u), ref, 4e-4) << u;
    }
}

TEST(Wavelengths, SampledPdfIsTheDensityAtTheSampledWavelength) {
    // sampleVisible takes p = (1 − t²)/norm from the tanh value t it inverted (1/cosh² = 1 − tanh²)
    // instead of evaluating visibleWavelengthPdf(λ) again. The two differ only by rounding: λ is
    // rounded to float (half an ulp ≤ 3.1e-5 nm at 830 nm) and |d ln p/dλ| = 2a|tanh| ≤ 0.0144/nm,
    // i.e. ≤ 4.4e-7 relative, plus a few float ulps (≤ 6e-7) in evaluating visibleWavelengthPdf.
    Pcg32 rng(11, 5);
    double worst = 0;
    for (int k = 0; k < 200000; ++k) {
        const SampledWavelengths wl = SampledWavelengths::sampleVisible(rng.uniform(), 1);
        const double p = visibleWavelengthPdf(wl.lambda(0));
        worst = std::max(worst, std::abs(wl.pdf(0) - p) / p);
    }
    EXPECT_LT(worst, 2e-6);
    // The end points of the range.
    for (float u : {0.0f, 0.99999994f}) {
        const SampledWavelengths wl = SampledWavelengths::sampleVisible(u, 1);
        EXPECT_NEAR(wl.pdf(0), visibleWavelengthPdf(wl.lambda(0)), 2e-6f * wl.pdf(0));
    }
}

TEST(Wavelengths, IndependentWavelengthsUseOneSampleEachWithTheSameMarginalPdf) {
    const float u[5] = {0.1f, 0.93f, 0.5f, 0.02f, 0.77f};
    const SampledWavelengths wl = SampledWavelengths::sampleIndependent(u, 5, false);
    ASSERT_EQ(wl.size(), 5);
    for (int i = 0; i < 5; ++i) {
        // Each is what the hero scheme would give for that primary sample with n = 1.
        const SampledWavelengths one = SampledWavelengths::sampleVisible(u[i], 1);
        EXPECT_EQ(wl.lambda(i), one.lambda(0)) << i;
        EXPECT_EQ(wl.pdf(i), one.pdf(0)) << i;
    }
    const SampledWavelengths uni = SampledWavelengths::sampleIndependent(u, 5, true);
    for (int i = 0; i < 5; ++i) {
        EXPECT_FLOAT_EQ(uni.lambda(i), kLambdaMin + u[i] * (kLambdaMax - kLambdaMin));
        EXPECT_FLOAT_EQ(uni.pdf(i), 1.0f / (kLambdaMax - kLambdaMin));
    }
    // Not stratified: two equal primary samples give two equal wavelengths (the hero scheme never does).
    const float same[2] = {0.3f, 0.3f};
    const SampledWavelengths twice = SampledWavelengths::sampleIndependent(same, 2, false);
    EXPECT_EQ(twice.lambda(0), twice.lambda(1));
    EXPECT_THROW(SampledWavelengths::sampleIndependent(u, 0, false), Error);
}
