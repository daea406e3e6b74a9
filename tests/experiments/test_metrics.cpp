// Image metrics: CIEDE2000 against the published test data, CIELAB of known colours, MSE / relMSE /
// PSNR on hand-computed cases, percentile ranks, per-pixel noise statistics.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>

#include "core/error.h"
#include "core/rng.h"
#include "metrics/color_difference.h"
#include "metrics/image_metrics.h"

using namespace iris;

namespace {

// The 34 pairs (L1, a1, b1, L2, a2, b2, ΔE00) of Table 1 in G. Sharma, W. Wu, E. N. Dalal, "The
// CIEDE2000 color-difference formula: implementation notes, supplementary test data, and
// mathematical observations", Color Research & Application 30(1):21–30, 2005 (published data).
const double kSharmaPairs[34][7] = {
    {50.0000, 2.6772, -79.7751, 50.0000, 0.0000, -82.7485, 2.0425},
    {50.0000, 3.1571, -77.2803, 50.0000, 0.0000, -82.7485, 2.8615},
    {50.0000, 2.8361, -74.0200, 50.0000, 0.0000, -82.7485, 3.4412},
    {50.0000, -1.3802, -84.2814, 50.0000, 0.0000, -82.7485, 1.0000},
    {50.0000, -1.1848, -84.8006, 50.0000, 0.0000, -82.7485, 1.0000},
    {50.0000, -0.9009, -85.5211, 50.0000, 0.0000, -82.7485, 1.0000},
    {50.0000, 0.0000, 0.0000, 50.0000, -1.0000, 2.0000, 2.3669},
    {50.0000, -1.0000, 2.0000, 50.0000, 0.0000, 0.0000, 2.3669},
    {50.0000, 2.4900, -0.0010, 50.0000, -2.4900, 0.0009, 7.1792},
    {50.0000, 2.4900, -0.0010, 50.0000, -2.4900, 0.0010, 7.1792},
    {50.0000, 2.4900, -0.0010, 50.0000, -2.4900, 0.0011, 7.2195},
    {50.0000, 2.4900, -0.0010, 50.0000, -2.4900, 0.0012, 7.2195},
    {50.0000, -0.0010, 2.4900, 50.0000, 0.0009, -2.4900, 4.8045},
    {50.0000, -0.0010, 2.4900, 50.0000, 0.0010, -2.4900, 4.8045},
    {50.0000, -0.0010, 2.4900, 50.0000, 0.0011, -2.4900, 4.7461},
    {50.0000, 2.5000, 0.0000, 50.0000, 0.0000, -2.5000, 4.3065},
    {50.0000, 2.5000, 0.0000, 73.0000, 25.0000, -18.0000, 27.1492},
    {50.0000, 2.5000, 0.0000, 61.0000, -5.0000, 29.0000, 22.8977},
    {50.0000, 2.5000, 0.0000, 56.0000, -27.0000, -3.0000, 31.9030},
    {50.0000, 2.5000, 0.0000, 58.0000, 24.0000, 15.0000, 19.4535},
    {50.0000, 2.5000, 0.0000, 50.0000, 3.1736, 0.5854, 1.0000},
    {50.0000, 2.5000, 0.0000, 50.0000, 3.2972, 0.0000, 1.0000},
    {50.0000, 2.5000, 0.0000, 50.0000, 1.8634, 0.5757, 1.0000},
    {50.0000, 2.5000, 0.0000, 50.0000, 3.2592, 0.3350, 1.0000},
    {60.2574, -34.0099, 36.2677, 60.4626, -34.1751, 39.4387, 1.2644},
    {63.0109, -31.0961, -5.8663, 62.8187, -29.7946, -4.0864, 1.2630},
    {61.2901, 3.7196, -5.3901, 61.4292, 2.2480, -4.9620, 1.8731},
    {35.0831, -44.1164, 3.7933, 35.0232, -40.0716, 1.5901, 1.8645},
    {22.7233, 20.0904, -46.6940, 23.0331, 14.9730, -42.5619, 2.0373},
    {36.4612, 47.8580, 18.3852, 36.2715, 50.5065, 21.2231, 1.4146},
    {90.8027, -2.0831, 1.4410, 91.1528, -1.6435, 0.0447, 1.4441},
    {90.9257, -0.5406, -0.9208, 88.6381, -0.8985, -0.7239, 1.5381},
    {6.7747, -0.2908, -2.4247, 5.8714, -0.0985, -2.2286, 0.6377},
    {2.0776, 0.0795, -1.1350, 0.9033, -0.0636, -0.5514, 0.9082},
};

Image constantImage(int w, int h, float r, float g, float b) {
    Image img(w, h, 3);
    for (size_t p = 0; p < img.pixelCount(); ++p) {
        img.pixels[3 * p] = r;
        img.pixels[3 * p + 1] = g;
        img.pixels[3 * p + 2] = b;
    }
    return img;
}

double gaussian(Pcg32& rng) {
    // Box–Muller transform.
    const double u1 = 1.0 - rng.uniformDouble(), u2 = rng.uniformDouble();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * 3.14159265358979323846 * u2);
}

}  // namespace

TEST(Metrics, Ciede2000MatchesSharmaTestData) {
    for (int i = 0; i < 34; ++i) {
        const double* p = kSharmaPairs[i];
        const Lab x{p[0], p[1], p[2]}, y{p[3], p[4], p[5]};
        EXPECT_NEAR(ciede2000(x, y), p[6], 1e-4) << "pair " << i + 1;
        EXPECT_NEAR(ciede2000(y, x), p[6], 1e-4) << "pair " << i + 1 << " swapped";
    }
    EXPECT_EQ(ciede2000(Lab{40, 10, -3}, Lab{40, 10, -3}), 0.0);
}

TEST(Metrics, LabOfReferenceColours) {
    const Lab white = linearRec709ToLab(1, 1, 1);
    EXPECT_NEAR(white.L, 100.0, 1e-9);
    EXPECT_NEAR(white.a, 0.0, 1e-9);
    EXPECT_NEAR(white.b, 0.0, 1e-9);
    const Lab black = linearRec709ToLab(0, 0, 0);
    EXPECT_NEAR(black.L, 0.0, 1e-9);
    // 18% grey: Y = 0.18 → L* = 116·0.18^(1/3) − 16 = 49.496.
    EXPECT_NEAR(linearRec709ToLab(0.18, 0.18, 0.18).L, 116.0 * std::cbrt(0.18) - 16.0, 1e-9);
    // Pure red: Y = 0.2126729 → L* = 53.24 (the well-known sRGB red lightness).
    const Lab red = linearRec709ToLab(1, 0, 0);
    EXPECT_NEAR(red.L, 53.24, 0.01);
    EXPECT_GT(red.a, 75.0);
    EXPECT_GT(red.b, 60.0);
}

TEST(Metrics, MseRelMsePsnrByHand) {
    // test = ref + 0.1 on every value: MSE = 0.01; relMSE = 0.01 / (r² + 0.01); PSNR = 20 dB.
    const Image ref = constantImage(4, 3, 0.3f, 0.3f, 0.3f);
    const Image test = constantImage(4, 3, 0.4f, 0.4f, 0.4f);
    const ImageErrors e = compareImages(test, ref);
    EXPECT_EQ(e.width, 4);
    EXPECT_EQ(e.channels, 3);
    EXPECT_NEAR(e.mse, 0.01, 1e-7);
    EXPECT_NEAR(e.relMse, 0.01 / (0.09 + 0.01), 1e-6);
    EXPECT_NEAR(e.psnr, 20.0, 1e-4);
    EXPECT_GT(e.meanDeltaE00, 0.5);
    EXPECT_NEAR(e.p99DeltaE00, e.meanDeltaE00, 1e-9);  // constant difference
    // PSNR clamps to [0,1]: values 2 vs 3 are both white.
    const ImageErrors bright = compareImages(constantImage(2, 2, 3, 3, 3), constantImage(2, 2, 2, 2, 2));
    EXPECT_NEAR(bright.mse, 1.0, 1e-9);
    EXPECT_TRUE(std::isinf(bright.psnr));
    const ImageErrors same = compareImages(ref, ref);
    EXPECT_EQ(same.mse, 0.0);
    EXPECT_EQ(same.meanDeltaE00, 0.0);
    EXPECT_TRUE(std::isinf(same.psnr));
}

TEST(Metrics, RelMseWeightsDarkPixelsMore) {
    // One value per image differs by 0.1: at r = 0 that value contributes 0.01/0.01 = 1, at r = 1 it
    // contributes 0.01/1.01; mean over 12 values.
    Image ref = constantImage(2, 2, 0, 0, 0), test = ref;
    test.at(1, 1, 2) = 0.1f;
    EXPECT_NEAR(compareImages(test, ref).relMse, 1.0 / 12.0, 1e-6);
    Image ref1 = constantImage(2, 2, 1, 1, 1), test1 = ref1;
    test1.at(1, 1, 2) = 1.1f;
    EXPECT_NEAR(compareImages(test1, ref1).relMse, 0.01 / 1.01 / 12.0, 1e-6);
}

TEST(Metrics, NonFiniteValuesAreCountedAndExcluded) {
    Image ref = constantImage(2, 1, 0.5f, 0.5f, 0.5f), test = ref;
    test.at(0, 0, 1) = std::numeric_limits<float>::quiet_NaN();
    test.at(1, 0, 0) = 0.7f;
    const ImageErrors e = compareImages(test, ref);
    EXPECT_EQ(e.nonFinite, 1u);
    EXPECT_NEAR(e.mse, 0.04 / 3.0, 1e-7);  // only the finite pixel: (0.2², 0, 0)
}

TEST(Metrics, MismatchedSizesThrow) {
    EXPECT_THROW(compareImages(Image(2, 2, 3), Image(2, 3, 3)), Error);
    EXPECT_THROW(compareImages(Image(2, 2, 3), Image(2, 2, 1)), Error);
}

TEST(Metrics, GreyImagesAreComparedAsGrey) {
    Image a(3, 1, 1), b(3, 1, 1);
    a.pixels = {0.2f, 0.2f, 0.2f};
    b.pixels = {0.2f, 0.3f, 0.2f};
    const ImageErrors e = compareImages(a, b);
    EXPECT_EQ(e.channels, 1);
    EXPECT_NEAR(e.mse, 0.01 / 3.0, 1e-7);
    const Lab la = linearRec709ToLab(0.2, 0.2, 0.2), lb = linearRec709ToLab(0.3, 0.3, 0.3);
    EXPECT_NEAR(e.maxDeltaE00, ciede2000(la, lb), 1e-6);
}

TEST(Metrics, PercentileNearestRank) {
    std::vector<double> v;
    for (int i = 100; i >= 1; --i) v.push_back(i);
    EXPECT_EQ(percentile(v, 99), 99.0);
    EXPECT_EQ(percentile(v, 100), 100.0);
    EXPECT_EQ(percentile(v, 50), 50.0);
    EXPECT_EQ(percentile(v, 0), 1.0);
    EXPECT_TRUE(std::isnan(percentile({}, 50)));
}

TEST(Metrics, DeltaEMapAndDifferenceImage) {
    Image ref = constantImage(2, 1, 0.5f, 0.5f, 0.5f), test = ref;
    test.at(1, 0, 0) = 0.6f;
    const Image map = deltaE00Map(test, ref);
    ASSERT_EQ(map.channels, 1);
    EXPECT_EQ(map.at(0, 0, 0), 0.0f);
    EXPECT_GT(map.at(1, 0, 0), 1.0f);
    const Image diff = differenceImage(test, ref);
    EXPECT_NEAR(diff.at(1, 0, 0), 0.1f, 1e-6f);
    EXPECT_EQ(diff.at(1, 0, 1), 0.0f);
}

TEST(Metrics, PixelStatisticsRecoverKnownVariance) {
    // k = 8 renders, each pixel value μ + σ·N(0,1) with σ² = 0.04. The mean over pixels of the unbiased
    // per-pixel variance estimate has standard error σ²·sqrt(2/(k−1))/sqrt(P) with P = 3·32·32 values.
    const int k = 8, w = 32, h = 32;
    const double sigma2 = 0.04;
    Pcg32 rng(1234, 5);
    std::vector<Image> renders;
    for (int i = 0; i < k; ++i) {
        Image img = constantImage(w, h, 0.5f, 0.25f, 0.1f);
        for (float& v : img.pixels) v += float(std::sqrt(sigma2) * gaussian(rng));
        renders.push_back(img);
    }
    const PixelStatistics s = pixelStatistics(renders);
    ASSERT_EQ(s.count, k);
    double meanVar = 0, meanVarOfMean = 0;
    for (size_t i = 0; i < s.variance.pixels.size(); ++i) {
        meanVar += s.variance.pixels[i];
        meanVarOfMean += s.varianceOfMean.pixels[i];
    }
    const double P = double(s.variance.pixels.size());
    meanVar /= P;
    meanVarOfMean /= P;
    const double se = sigma2 * std::sqrt(2.0 / (k - 1)) / std::sqrt(P);
    EXPECT_NEAR(meanVar, sigma2, 4 * se);
    EXPECT_NEAR(meanVarOfMean, sigma2 / k, 4 * se / k);
    EXPECT_NEAR(s.mean.at(3, 4, 0), 0.5, 4 * std::sqrt(sigma2 / k));
    EXPECT_THROW(pixelStatistics({renders[0]}), Error);
}

TEST(Metrics, CompareWithinNoiseDetectsBias) {
    // Two independent noisy estimates of the same image: mean z² ≈ 1 (its standard error is
    // sqrt(2/P) for P values); a bias of 3σ makes mean z² ≈ 1 + 9/2.
    const int w = 64, h = 64;
    const double sigma2 = 0.01;
    Pcg32 rng(99, 1);
    Image a = constantImage(w, h, 0.4f, 0.4f, 0.4f), b = a, var = a;
    for (float& v : var.pixels) v = float(sigma2);
    for (float& v : a.pixels) v += float(std::sqrt(sigma2) * gaussian(rng));
    for (float& v : b.pixels) v += float(std::sqrt(sigma2) * gaussian(rng));
    const NoiseComparison ok = compareWithinNoise(a, var, b, var);
    const double P = 3.0 * w * h;
    EXPECT_EQ(ok.count, size_t(P));
    EXPECT_NEAR(ok.meanSquaredZ, 1.0, 4 * std::sqrt(2.0 / P));
    EXPECT_LT(ok.fractionAbove3, 0.01);
    Image biased = b;
    for (float& v : biased.pixels) v += float(3.0 * std::sqrt(2.0 * sigma2));
    const NoiseComparison bad = compareWithinNoise(a, var, biased, var);
    EXPECT_GT(bad.meanSquaredZ, 5.0);
    EXPECT_GT(bad.fractionAbove3, 0.3);
}

TEST(Metrics, SmapeAndPerChannelErrors) {
    // SMAPE = mean |x − r| / (|x| + |r| + 0.01): 0.1 / 0.71 for 0.4 vs 0.3; 0 when equal; < 1 always.
    Image test(2, 1, 3), ref(2, 1, 3);
    for (float& v : ref.pixels) v = 0.3f;
    test.pixels = {0.4f, 0.4f, 0.4f, 0.3f, 0.3f, 0.3f};
    EXPECT_NEAR(compareImages(test, ref).smape, 0.5 * 0.1 / 0.71, 1e-7);
    EXPECT_EQ(compareImages(ref, ref).smape, 0.0);
    test.pixels = {1e6f, 1e6f, 1e6f, 0.3f, 0.3f, 0.3f};
    EXPECT_LT(compareImages(test, ref).smape, 0.5);
    // Per channel (named bands, as a spectral image has): only channel "B" differs here.
    Image a(3, 2, 3), b(3, 2, 3);
    for (size_t p = 0; p < a.pixelCount(); ++p) a.pixels[3 * p + 2] = 0.5f;
    const std::vector<ChannelErrors> ch = channelErrors(a, b);
    ASSERT_EQ(ch.size(), 3u);
    EXPECT_EQ(ch[2].name, "B");
    EXPECT_EQ(ch[2].count, 6u);
    EXPECT_NEAR(ch[2].mse, 0.25, 1e-9);
    EXPECT_NEAR(ch[2].relMse, 0.25 / 0.01, 1e-6);
    EXPECT_NEAR(ch[2].smape, 0.5 / 0.51, 1e-7);
    EXPECT_EQ(ch[0].mse, 0.0);
    EXPECT_THROW(channelErrors(a, b, {"S0.550nm"}), Error);  // a band the images do not have
    EXPECT_EQ(channelErrors(a, b, {"G"}).size(), 1u);
}

TEST(Metrics, XyzToLinearRec709InvertsTheSrgbMatrix) {
    for (const std::array<double, 3> rgb : {std::array<double, 3>{0.2, 0.5, 0.9}, std::array<double, 3>{1, 0, 0}}) {
        double xyz[3], back[3];
        linearRec709ToXYZ(rgb[0], rgb[1], rgb[2], xyz);
        xyzToLinearRec709(xyz, back);
        for (int k = 0; k < 3; ++k) EXPECT_NEAR(back[k], rgb[k], 1e-12);
    }
    double white[3];
    rec709WhiteXYZ(white);
    EXPECT_NEAR(white[0], 0.95047, 1e-5);
    EXPECT_NEAR(white[1], 1.0, 1e-6);
    EXPECT_NEAR(white[2], 1.08883, 1e-5);
}
