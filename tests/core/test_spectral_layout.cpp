// The OpenEXR spectral layout of Fichet et al. 2021 (core/io/spectral_layout.h): channel names
// with a decimal comma, parsing of the names other writers use, and extraction sorted by wavelength.
#include <gtest/gtest.h>

#include "core/error.h"
#include "core/io/spectral_layout.h"

using namespace iris;

TEST(SpectralLayout, ChannelNamesUseTheLayoutsDecimalComma) {
    EXPECT_EQ(spectralChannelName(552.5), "S0.552,500000nm");
    EXPECT_EQ(spectralChannelName(400.0), "S0.400,000000nm");
    EXPECT_EQ(parseSpectralChannelName(spectralChannelName(552.5)).value(), 552.5);
}

TEST(SpectralLayout, ParsesCommaAndPointButNothingElse) {
    EXPECT_EQ(parseSpectralChannelName("S0.550nm").value(), 550.0);
    EXPECT_EQ(parseSpectralChannelName("S0.550,25nm").value(), 550.25);
    EXPECT_EQ(parseSpectralChannelName("S0.550.25nm").value(), 550.25);
    for (const char* bad : {"R", "S1.550nm", "S0.nm", "S0.abcnm", "S0.550", "T.550nm", "S0.-5nm", "S0.5,5,5nm"})
        EXPECT_FALSE(parseSpectralChannelName(bad).has_value()) << bad;
}

TEST(SpectralLayout, ChannelsAreExtractedSortedByWavelength) {
    Image img(2, 1, 4);
    img.channelNames = {"S0.600nm", "R", "S0.500nm", "S0.550nm"};
    for (size_t i = 0; i < img.pixels.size(); ++i) img.pixels[i] = float(i);
    const SpectralImage s = spectralChannels(img, "x.exr");
    ASSERT_EQ(s.bins(), 3);
    EXPECT_EQ(s.wavelengths, (std::vector<double>{500, 550, 600}));
    // pixel 1 holds values 4..7 in channel order 600, R, 500, 550.
    EXPECT_EQ(s.values[3], 6.0f);
    EXPECT_EQ(s.values[4], 7.0f);
    EXPECT_EQ(s.values[5], 4.0f);
    EXPECT_TRUE(hasSpectralChannels(img));
    EXPECT_FALSE(hasSpectralChannels(Image(2, 1, 3)));
}

TEST(SpectralLayout, ImagesWithoutOrWithDuplicateBandsAreRejectedNamingTheFile) {
    try {
        spectralChannels(Image(2, 2, 3), "plain.exr");
        FAIL();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("plain.exr: no spectral channels"), std::string::npos) << e.what();
    }
    Image dup(1, 1, 2);
    dup.channelNames = {"S0.550nm", "S0.550,0nm"};
    EXPECT_THROW(spectralChannels(dup, "dup.exr"), Error);
}
