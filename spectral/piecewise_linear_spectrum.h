// A spectrum tabulated at arbitrary increasing wavelengths, linearly interpolated (measured data:
// .spd files, <spectrum value="λ:v, ..."/>). Outside the table a reflectance or an illuminant is 0,
// as in Mitsuba (0.6 InterpolatedSpectrum, 3 `irregular`: a tabulated spectrum has no energy
// where it has no data); an Unbounded spectrum (IOR n and k) keeps its end values, since an index
// of 0 has no physical meaning (a deliberate difference from Mitsuba, docs/scene_format.md).
#pragma once

#include <cstdint>
#include <vector>

#include "spectral/spectrum.h"

namespace iris {

class PiecewiseLinearSpectrum final : public Spectrum {
public:
    /// lambdas strictly increasing (nm), same size as values, non-empty, all finite; else iris::Error.
    PiecewiseLinearSpectrum(std::vector<float> lambdas, std::vector<float> values, SpectrumKind kind);

    float eval(float lambda) const override;
    float maxValue() const override { return max_; }
    vec3 rgbValue() const override { return rgb_; }

    const std::vector<float>& lambdas() const { return lambdas_; }
    const std::vector<float>& values() const { return values_; }

private:
    /// Index of the first sample strictly above lambda (std::upper_bound), for lambda inside
    /// (front, back): a uniform bucket grid over the table gives a start index, from which a short
    /// walk finds the same index as the binary search (tests/spectral/test_spectra.cpp compares them).
    size_t upperIndex(float lambda) const;

    bool zeroOutside_;
    std::vector<float> lambdas_, values_;
    std::vector<uint32_t> bucketStart_;  // upper_bound of each bucket's lower edge
    float bucketScale_ = 0;              // buckets per nm
    float max_ = 0;
    vec3 rgb_{0.0f};
};

}  // namespace iris
