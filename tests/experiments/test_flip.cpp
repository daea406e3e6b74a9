// FLIP (metrics/flip.h): invariants of the HPG 2020 paper and of HDR-FLIP (EG 2021),
// the colour pipeline's documented intermediate values, analytic values for uniform images, and
// the order of values for known differences. docs/metrics.md ("FLIP") lists what is validated.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/error.h"
#include "core/rng.h"
#include "metrics/color_difference.h"
#include "metrics/flip.h"

using namespace iris;

namespace {

Image uniform(int w, int h, double r, double g, double b) {
    Image img(w, h, 3);
    for (size_t p = 0; p < img.pixelCount(); ++p) {
        img.pixels[3 * p] = float(r);
        img.pixels[3 * p + 1] = float(g);
        img.pixels[3 * p + 2] = float(b);
    }
    return img;
}

/// grey + Gaussian noise of standard deviation sigma (Box–Muller, fixed seed).
Image noisyGrey(int w, int h, double grey, double sigma, uint64_t seed) {
    Image img = uniform(w, h, grey, grey, grey);
    Pcg32 rng(seed, 7);
    for (float& v : img.pixels) {
        const double u1 = std::max(1e-12, rng.uniformDouble()), u2 = rng.uniformDouble();
        v = float(grey + sigma * std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2));
    }
    return img;
}

/// CIELAB L* of a grey linear value (CIE 15:2004), written out here independently of the metric.
double lightnessOfGrey(double y) { return y > 216.0 / 24389.0 ? 116.0 * std::cbrt(y) - 16.0 : y * 24389.0 / 27.0; }

/// FLIP of two uniform grey images by the paper's colour pipeline alone (no features, filtering
/// leaves constants unchanged, Hunt-adjusted a, b are 0 for greys): remap(|ΔL*|^q_c).
double uniformGreyFlip(double a, double b) {
    const double cmax = 41.2761;  // §4.1.3 (≈ 41; the authors' implementation gives 41.2761)
    const double d = std::pow(std::abs(lightnessOfGrey(a) - lightnessOfGrey(b)), 0.7);
    return d < 0.4 * cmax ? d * 0.95 / (0.4 * cmax) : 0.95 + (d - 0.4 * cmax) / (0.6 * cmax) * 0.05;
}

double maxOf(const Image& img) {
    double m = -std::numeric_limits<double>::infinity();
    for (float v : img.pixels) m = std::max(m, double(v));
    return m;
}

}  // namespace

TEST(Flip, ViewingConditionsAndConstantsOfThePaper) {
    // §5: 0.7 m from a 0.7 m wide monitor with 3840 pixels per line → 67.02 pixels per degree.
    EXPECT_NEAR(flip::pixelsPerDegree(), 67.0206, 1e-4);
    EXPECT_NEAR(flip::pixelsPerDegree(0.7, 0.7, 1920), 67.0206 / 2, 1e-4);
    // §4.1.3: the largest Hunt-adjusted HyAB distance is green–blue, ≈ 203, ≈ 41 after ^0.7.
    double green[3], blue[3];
    flip::huntLab(0, 1, 0, green);
    flip::huntLab(0, 0, 1, blue);
    EXPECT_NEAR(flip::hyab(green, blue), 203.0, 0.5);
    EXPECT_NEAR(flip::colorMax(), 41.2761, 1e-3);
    // The remapping is continuous at p_c c_max (value p_t) and reaches 1 at c_max.
    const double knee = 0.4 * flip::colorMax();
    EXPECT_NEAR(flip::remapColorError(knee - 1e-9), 0.95, 1e-8);
    EXPECT_NEAR(flip::remapColorError(knee), 0.95, 1e-12);
    EXPECT_NEAR(flip::remapColorError(flip::colorMax()), 1.0, 1e-12);
    EXPECT_EQ(flip::remapColorError(0.0), 0.0);
}

TEST(Flip, NoGamutColourPairIsFurtherApartThanGreenAndBlue) {
    // c_max is the normaliser of §4.1.3: every pair of in-gamut colours must lie within it.
    Pcg32 rng(11, 3);
    double worst = 0;
    for (int i = 0; i < 200000; ++i) {
        double x[3], y[3];
        flip::huntLab(rng.uniform(), rng.uniform(), rng.uniform(), x);
        flip::huntLab(rng.uniform(), rng.uniform(), rng.uniform(), y);
        worst = std::max(worst, std::pow(flip::hyab(x, y), flip::kQc));
    }
    // All eight corners of the RGB cube too.
    for (int a = 0; a < 8; ++a)
        for (int b = 0; b < 8; ++b) {
            double x[3], y[3];
            flip::huntLab(a & 1, (a >> 1) & 1, (a >> 2) & 1, x);
            flip::huntLab(b & 1, (b >> 1) & 1, (b >> 2) & 1, y);
            worst = std::max(worst, std::pow(flip::hyab(x, y), flip::kQc));
        }
    EXPECT_LE(worst, flip::colorMax() + 1e-9);
}

TEST(Flip, FiltersAreNormalisedAsThePaperSays) {
    const double ppd = flip::pixelsPerDegree();
    // §4.1.1: radius ⌈3 sqrt(0.04 / (2π²)) · 67.02⌉ = ⌈9.05⌉ = 10 pixels.
    EXPECT_EQ(flip::csfRadius(ppd), 10);
    EXPECT_EQ(flip::csfGaussian(0.0047, ppd).size(), 21u);
    const flip::FeatureFilters f = flip::featureFilters(ppd);
    // §4.2.1: σ = ½ · 0.082 · 67.02 = 2.748 pixels, radius ⌈3σ⌉ = 9.
    ASSERT_EQ(f.gauss.size(), 19u);
    double g = 0, pos1 = 0, neg1 = 0, pos2 = 0, neg2 = 0;
    for (size_t i = 0; i < f.gauss.size(); ++i) {
        g += f.gauss[i];
        (f.first[i] > 0 ? pos1 : neg1) += f.first[i];
        (f.second[i] > 0 ? pos2 : neg2) += f.second[i];
    }
    EXPECT_NEAR(g, 1.0, 1e-12);
    EXPECT_NEAR(pos1, 1.0, 1e-12);
    EXPECT_NEAR(neg1, -1.0, 1e-12);
    EXPECT_NEAR(pos2, 1.0, 1e-12);
    EXPECT_NEAR(neg2, -1.0, 1e-12);
    EXPECT_GT(f.first.front(), 0.0);   // −x e^{…}: positive on the left
    EXPECT_LT(f.second[9], 0.0);      // centre of (x²/σ² − 1) e^{…}
}

TEST(Flip, IdenticalImagesGiveExactlyZero) {
    const Image img = noisyGrey(24, 20, 0.4, 0.3, 5);
    const FlipResult ldr = ldrFlip(img, img), hdr = hdrFlip(img, img);
    EXPECT_EQ(ldr.mean, 0.0);
    EXPECT_EQ(hdr.mean, 0.0);
    EXPECT_EQ(maxOf(ldr.map), 0.0);
    EXPECT_EQ(maxOf(hdr.map), 0.0);
}

TEST(Flip, UniformImagesGiveTheColourPipelinesValue) {
    // Filters leave a constant image unchanged and find no features, so FLIP = remap(HyAB^q_c).
    // Black vs white: HyAB = 100, 100^0.7 = 25.12 > p_c c_max → 0.95 + (25.12 − 16.51)/24.77 · 0.05.
    const FlipResult bw = ldrFlip(uniform(16, 16, 0, 0, 0), uniform(16, 16, 1, 1, 1));
    EXPECT_NEAR(uniformGreyFlip(0, 1), 0.96738, 1e-5);
    EXPECT_NEAR(bw.mean, uniformGreyFlip(0, 1), 1e-4);
    for (const auto& [a, b] : {std::pair{0.5, 0.25}, {0.18, 0.2}, {0.02, 0.9}}) {
        const FlipResult r = ldrFlip(uniform(12, 10, a, a, a), uniform(12, 10, b, b, b));
        EXPECT_NEAR(r.mean, uniformGreyFlip(a, b), 1e-4) << a << " vs " << b;
        EXPECT_NEAR(maxOf(r.map), r.mean, 1e-6);
    }
    // Values above 1 are clamped by LDR-FLIP: 2 vs 1 is no difference.
    EXPECT_EQ(ldrFlip(uniform(8, 8, 2, 2, 2), uniform(8, 8, 1, 1, 1)).mean, 0.0);
}

TEST(Flip, ValuesLieInTheUnitIntervalAndAreSymmetric) {
    for (uint64_t seed = 1; seed <= 3; ++seed) {
        const Image a = noisyGrey(20, 18, 0.5, 0.6, seed), b = noisyGrey(20, 18, 0.3, 0.6, seed + 10);
        for (const FlipResult& r : {ldrFlip(a, b), hdrFlip(a, b)})
            for (float v : r.map.pixels) {
                EXPECT_GE(v, 0.0f);
                EXPECT_LE(v, 1.0f);
            }
        // Colour (HyAB) and feature (absolute difference) terms are symmetric in test and reference.
        const FlipResult ab = ldrFlip(a, b), ba = ldrFlip(b, a);
        for (size_t p = 0; p < ab.map.pixels.size(); ++p) EXPECT_NEAR(ab.map.pixels[p], ba.map.pixels[p], 1e-6f);
    }
}

TEST(Flip, ErrorGrowsWithNoiseAndSmallNoiseIsNearlyInvisible) {
    const Image ref = uniform(48, 48, 0.18, 0.18, 0.18);
    double previous = 0;
    for (double sigma : {0.002, 0.01, 0.04, 0.16}) {
        const double m = ldrFlip(noisyGrey(48, 48, 0.18, sigma, 3), ref).mean;
        EXPECT_GT(m, previous) << sigma;
        previous = m;
    }
    // σ = 0.002 on a mid grey (ΔL* ≈ 0.4 per pixel before filtering) stays far below p_t.
    EXPECT_LT(ldrFlip(noisyGrey(48, 48, 0.18, 0.002, 3), ref).mean, 0.05);
    // Heavy noise (σ of the order of the value: mean ΔE00 ≈ 28) is a large, clearly visible
    // difference, well above the small-noise case (measured 0.28).
    EXPECT_GT(ldrFlip(noisyGrey(48, 48, 0.18, 0.16, 3), ref).mean, 0.2);
}

TEST(Flip, AFireflyIsALargeLocalError) {
    // §4.2: point features make an isolated bright pixel count fully, while filtering alone
    // would spread and dim it.
    const Image ref = uniform(33, 33, 0.1, 0.1, 0.1);
    Image test = ref;
    for (int c = 0; c < 3; ++c) test.at(16, 16, c) = 1.0f;
    const FlipResult r = ldrFlip(test, ref);
    EXPECT_GT(r.map.at(16, 16, 0), 0.5f);
    EXPECT_LT(r.map.at(0, 0, 0), 0.01f);  // far from the firefly
    EXPECT_LT(r.mean, 0.05);              // one pixel of 1089
}

TEST(Flip, HdrExposuresFollowTheReferenceLuminance) {
    // HDR-FLIP §2: c_start maps the largest luminance and c_stop the median to 0.85 after ACES.
    for (double t : {0.1, 0.5, 0.85, 0.99}) EXPECT_NEAR(flip::toneMapAces(flip::inverseToneMapAces(t)), t, 1e-12);
    EXPECT_EQ(flip::toneMapAces(0.0), 0.0);
    Image ref = uniform(10, 10, 0.5, 0.5, 0.5);  // Y = 0.5 (white-balanced grey)
    for (int c = 0; c < 3; ++c) ref.at(3, 4, c) = 64.0f;
    const FlipExposures e = hdrFlipExposures(ref);
    const double x = flip::inverseToneMapAces(0.85);
    EXPECT_NEAR(e.start, std::log2(x / 64.0), 1e-5);
    EXPECT_NEAR(e.stop, std::log2(x / 0.5), 1e-5);
    EXPECT_EQ(e.count, 7);  // ⌈log2(64 / 0.5)⌉ = 7
    EXPECT_EQ(hdrFlipExposures(uniform(4, 4, 0, 0, 0)).count, 2);  // black: never fewer than 2
}

TEST(Flip, HdrFlipIsInvariantToAPowerOfTwoExposureOfBothImages) {
    // Scaling both images by 2 shifts every exposure by −1 stop: the exposed images are the same.
    const Image a = noisyGrey(20, 20, 1.5, 1.0, 4), b = noisyGrey(20, 20, 1.5, 1.0, 9);
    Image a2 = a, b2 = b;
    for (float& v : a2.pixels) v *= 2;
    for (float& v : b2.pixels) v *= 2;
    const FlipResult r1 = hdrFlip(a, b), r2 = hdrFlip(a2, b2);
    EXPECT_NEAR(r2.exposures.start, r1.exposures.start - 1, 1e-6);
    EXPECT_NEAR(r2.mean, r1.mean, 1e-5);
    EXPECT_GT(r1.mean, 0.05);
    // A difference only in highlights above 1 is invisible to LDR-FLIP but not to HDR-FLIP.
    Image hot = uniform(16, 16, 0.2, 0.2, 0.2), hotter = hot;
    for (int y = 4; y < 12; ++y)
        for (int x = 4; x < 12; ++x)
            for (int c = 0; c < 3; ++c) hot.at(x, y, c) = 4.0f, hotter.at(x, y, c) = 8.0f;
    EXPECT_EQ(ldrFlip(hotter, hot).mean, 0.0);
    EXPECT_GT(hdrFlip(hotter, hot).mean, 0.05);
}

TEST(Flip, MismatchedImagesAndNonFinitePixels) {
    EXPECT_THROW(ldrFlip(uniform(4, 4, 0, 0, 0), uniform(5, 4, 0, 0, 0)), Error);
    Image a = uniform(8, 8, 0.3, 0.3, 0.3), b = a;
    a.at(2, 2, 1) = std::numeric_limits<float>::quiet_NaN();
    const FlipResult r = ldrFlip(a, b);
    EXPECT_TRUE(std::isnan(r.map.at(2, 2, 0)));
    EXPECT_TRUE(std::isfinite(r.mean));
}
