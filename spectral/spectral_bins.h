// Wavelength bins of a spectral image (render --spectral-output, docs/spectral.md "Spectral
// images"): [λmin, λmax] cut into equal bins of a chosen width (which must divide the range), or
// the bins around the channel wavelengths of a file. A bin's value is the mean spectral radiance over
// the bin, (1/Δ_b) ∫_b L(λ) dλ, so a constant spectrum has the same value in every bin.
#pragma once

#include <vector>

#include "core/io/spectral_layout.h"
#include "core/math.h"
#include "spectral/wavelengths.h"

namespace iris {

class SpectralBins {
public:
    /// Equal bins; throws iris::Error unless λmin < λmax inside [kLambdaMin, kLambdaMax] and the
    /// width divides λmax − λmin (to 1e-6 nm), naming the widths that would.
    explicit SpectralBins(double width, double lambdaMin = kLambdaMin, double lambdaMax = kLambdaMax);
    /// The bins of a file that names only its channel wavelengths (increasing, at least 2): edges
    /// midway between neighbours, the outer edges half a spacing out, clipped to [kLambdaMin,
    /// kLambdaMax]. Equal bins give back their own edges. Throws iris::Error for fewer than 2 or
    /// non-increasing wavelengths.
    static SpectralBins fromCentres(const std::vector<double>& centres);

    int count() const { return int(edges_.size()) - 1; }
    double lower(int b) const { return edges_[size_t(b)]; }
    double upper(int b) const { return edges_[size_t(b) + 1]; }
    double width(int b) const { return upper(b) - lower(b); }
    double centre(int b) const { return 0.5 * (lower(b) + upper(b)); }
    /// Bin holding λ (the upper edge belongs to the last bin), or -1 outside [λmin, λmax].
    int find(double lambda) const;

    /// ∫_b (x̄, ȳ, z̄) dλ / ∫ȳ dλ: the XYZ of a spectrum that is 1 in bin b and 0 elsewhere, with the
    /// CMFs integrated exactly as the piecewise-linear functions cie::xyzBar interpolates and the
    /// normalisation of toXYZ (cie::yIntegral, docs/conventions.md).
    const dvec3& xyzWeight(int b) const { return xyzWeight_[size_t(b)]; }
    /// XYZ of binned mean radiances `values` (count() of them, by bin): Σ_b value_b · xyzWeight(b).
    dvec3 toXYZ(const float* values) const;

private:
    SpectralBins() = default;
    void computeWeights();
    std::vector<double> edges_;
    std::vector<dvec3> xyzWeight_;
};

/// The CIE XYZ image (channels X, Y, Z) of a spectral image, each pixel Σ_b value_b·xyzWeight(b)
/// over the bins fromCentres(wavelengths) (equal bins of an iris file give back their own edges).
Image xyzImage(const SpectralImage& s);

}  // namespace iris
