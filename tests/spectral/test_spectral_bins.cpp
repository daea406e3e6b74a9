// Wavelength bins of spectral images (spectral/spectral_bins.h): layout, lookup, the XYZ weights
// (exact integrals of the interpolated CMFs) and the errors for widths that do not divide the range.
#include <gtest/gtest.h>

#include "core/error.h"
#include "spectral/cie.h"
#include "spectral/spectral_bins.h"
#include "spectral/xyz.h"

using namespace iris;

TEST(SpectralBins, EqualBinsCoverTheVisibleRange) {
    const SpectralBins b(5.0);
    ASSERT_EQ(b.count(), 94);
    EXPECT_EQ(b.lower(0), 360.0);
    EXPECT_EQ(b.upper(93), 830.0);
    EXPECT_EQ(b.centre(38), 552.5);
    EXPECT_EQ(b.find(360.0), 0);
    EXPECT_EQ(b.find(364.999), 0);
    EXPECT_EQ(b.find(365.0), 1);
    EXPECT_EQ(b.find(830.0), 93);  // the upper edge belongs to the last bin
    EXPECT_EQ(b.find(359.9), -1);
    EXPECT_EQ(b.find(830.1), -1);
    EXPECT_EQ(SpectralBins(10.0).count(), 47);
    EXPECT_EQ(SpectralBins(1.0).count(), 470);
}

TEST(SpectralBins, WidthThatDoesNotDivideTheRangeIsRejectedWithTheWidthsThatDo) {
    try {
        SpectralBins b(4.0);
        FAIL() << "4 nm bins accepted";
    } catch (const Error& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("4 nm does not divide"), std::string::npos) << m;
        EXPECT_NE(m.find(" 5"), std::string::npos) << m;
    }
    EXPECT_THROW(SpectralBins(0.0), Error);
    EXPECT_THROW(SpectralBins(-5.0), Error);
    EXPECT_THROW(SpectralBins(5.0, 300.0, 830.0), Error);
}

TEST(SpectralBins, WeightsOfAllBinsSumToTheXyzOfAConstantSpectrum) {
    // Σ_b xyzWeight(b) = ∫ cmf / ∫ȳ: the exact integral of the interpolated CMFs over 360–830 nm
    // (trapezoid on the 1 nm nodes) against the 1 nm rectangle rule of toXYZ's normalisation and
    // integrateXYZ: they differ by half the end values, ~1e-7 of the total.
    for (double w : {1.0, 5.0, 10.0, 47.0}) {
        const SpectralBins b(w);
        dvec3 sum(0.0);
        for (int i = 0; i < b.count(); ++i) sum += b.xyzWeight(i);
        const dvec3 flat = integrateXYZ([](float) { return 1.0f; });
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(sum[c], flat[c], 1e-5 * flat[c]) << "width " << w << " channel " << c;
    }
}

TEST(SpectralBins, OneBinHoldsTheIntegralOfItsInterpolatedCmf) {
    // Bin [550, 555]: the CMFs are linear between 1 nm nodes, so the integral is the trapezoid sum.
    const SpectralBins b(5.0);
    const int i = b.find(552.0);
    double y = 0;
    for (int l = 550; l < 555; ++l) y += 0.5 * (cie::yBar(float(l)) + cie::yBar(float(l + 1)));
    EXPECT_NEAR(b.xyzWeight(i).y, y / cie::yIntegral(), 1e-7 * b.xyzWeight(i).y);  // float table values
}

TEST(SpectralBins, FromCentresGivesEqualBinsBackAndRejectsBadLists) {
    const SpectralBins equal(10.0);
    std::vector<double> centres;
    for (int i = 0; i < equal.count(); ++i) centres.push_back(equal.centre(i));
    const SpectralBins back = SpectralBins::fromCentres(centres);
    ASSERT_EQ(back.count(), equal.count());
    for (int i = 0; i < equal.count(); ++i) {
        EXPECT_EQ(back.lower(i), equal.lower(i));
        EXPECT_EQ(back.upper(i), equal.upper(i));
    }
    EXPECT_THROW(SpectralBins::fromCentres({550.0}), Error);
    EXPECT_THROW(SpectralBins::fromCentres({550.0, 540.0}), Error);
}

TEST(SpectralBins, WavelengthsFarOutsideTheTablesGiveTheSameWeightsAtOnce) {
    // A spectral image from a file may name any wavelengths: 1e20 nm once made the CMF integral
    // step through [500, 5e19] nm one nanometre at a time (found by fuzz_image). Beyond the tables
    // the CMFs are 0, so its bins weigh exactly what bins ending at 1e6 nm do.
    const SpectralBins huge = SpectralBins::fromCentres({400.0, 1e20}), wide = SpectralBins::fromCentres({400.0, 1e6});
    ASSERT_EQ(huge.count(), wide.count());
    EXPECT_EQ(huge.xyzWeight(0), wide.xyzWeight(0));
    EXPECT_GT(huge.xyzWeight(0).y, 0.99);  // the first bin holds the whole visible range: Y ≈ 1
    const SpectralBins low = SpectralBins::fromCentres({-1e20, 500.0, 600.0});
    EXPECT_EQ(low.xyzWeight(1), SpectralBins::fromCentres({-1e6, 500.0, 600.0}).xyzWeight(1));
}
