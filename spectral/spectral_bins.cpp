#include "spectral/spectral_bins.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "spectral/cie.h"
#include "spectral/wavelengths.h"

namespace iris {

namespace {

/// ∫_a^b of the piecewise-linear interpolant of the 1 nm CMF table: the trapezoid rule between the
/// table nodes inside [a, b] and at the two cut points is exact for a piecewise-linear function.
/// Outside [kLambdaMin − 1, kLambdaMax + 1] nm (the table's range, spectral/wavelengths.h) the
/// interpolant is 0 on whole unit steps, which add nothing, so [a, b] is clipped there: the same
/// sum bit for bit, and at most ~470 steps for any bounds (the wavelengths of a spectral image read
/// from a file can be anything: 1e20 nm made this loop run for ever, found by fuzz_image).
dvec3 integrateXyzBar(double a, double b) {
    a = std::max(a, double(kLambdaMin) - 1.0);
    b = std::min(b, double(kLambdaMax) + 1.0);
    dvec3 sum(0.0);
    double x0 = a;
    while (x0 < b) {
        const double x1 = std::min(b, std::floor(x0) + 1.0);
        sum += 0.5 * (x1 - x0) * (dvec3(cie::xyzBar(float(x0))) + dvec3(cie::xyzBar(float(x1))));
        x0 = x1;
    }
    return sum;
}

}  // namespace

SpectralBins::SpectralBins(double width, double lambdaMin, double lambdaMax) {
    if (!(width > 0) || !std::isfinite(width)) fail("spectral bin width must be a positive number of nm, got ", width);
    if (!(lambdaMin >= kLambdaMin && lambdaMax <= kLambdaMax && lambdaMin < lambdaMax))
        fail("spectral bins must lie in [", kLambdaMin, ", ", kLambdaMax, "] nm, got [", lambdaMin, ", ", lambdaMax, "]");
    const double range = lambdaMax - lambdaMin;
    const long n = std::lround(range / width);
    if (n < 1 || std::abs(double(n) * width - range) > 1e-6) {
        std::string ok;
        for (long k = 1; k <= long(range); ++k)
            if (std::abs(range / double(k) - std::round(range / double(k))) < 1e-9 && range / double(k) <= 50.0)
                ok += (ok.empty() ? "" : ", ") + strCat(range / double(k));
        fail("spectral bin width ", width, " nm does not divide [", lambdaMin, ", ", lambdaMax, "] nm into equal bins (widths that do, up to 50 nm: ", ok, ")");
    }
    for (long b = 0; b < n; ++b) edges_.push_back(lambdaMin + double(b) * width);
    edges_.push_back(lambdaMax);
    computeWeights();
}

SpectralBins SpectralBins::fromCentres(const std::vector<double>& c) {
    if (c.size() < 2) fail("a spectral image needs at least 2 wavelengths to define its bins, got ", c.size());
    for (size_t i = 1; i < c.size(); ++i)
        if (!(c[i] > c[i - 1])) fail("spectral channel wavelengths must increase, got ", c[i - 1], " then ", c[i], " nm");
    SpectralBins bins;
    bins.edges_.push_back(std::max(double(kLambdaMin), c[0] - 0.5 * (c[1] - c[0])));
    for (size_t i = 1; i < c.size(); ++i) bins.edges_.push_back(0.5 * (c[i - 1] + c[i]));
    bins.edges_.push_back(std::min(double(kLambdaMax), c.back() + 0.5 * (c.back() - c[c.size() - 2])));
    bins.computeWeights();
    return bins;
}

void SpectralBins::computeWeights() {
    xyzWeight_.clear();
    for (int b = 0; b < count(); ++b) xyzWeight_.push_back(integrateXyzBar(lower(b), upper(b)) / cie::yIntegral());
}

int SpectralBins::find(double lambda) const {
    if (!(lambda >= edges_.front() && lambda <= edges_.back())) return -1;
    const auto it = std::upper_bound(edges_.begin(), edges_.end(), lambda);
    return std::min(int(it - edges_.begin()) - 1, count() - 1);
}

dvec3 SpectralBins::toXYZ(const float* values) const {
    dvec3 xyz(0.0);
    for (int b = 0; b < count(); ++b) xyz += double(values[b]) * xyzWeight_[size_t(b)];
    return xyz;
}

Image xyzImage(const SpectralImage& s) {
    const SpectralBins bins = SpectralBins::fromCentres(s.wavelengths);
    Image img(s.width, s.height, 3);
    img.channelNames = {"X", "Y", "Z"};
    for (size_t p = 0; p < img.pixelCount(); ++p) {
        const dvec3 xyz = bins.toXYZ(&s.values[p * size_t(s.bins())]);
        for (int c = 0; c < 3; ++c) img.pixels[3 * p + size_t(c)] = float(xyz[c]);
    }
    return img;
}

}  // namespace iris
