// Spectra given as a linear Rec.709 RGB triple (spectral/spectrum_factory.h, makeRGBSpectrum):
//   Reflectance: s(λ), the Jakob–Hanika sigmoid polynomial fitted to rgb ∈ [0,1]³ (bounded [0,1]);
//                near-black colours (max < kDarkLevel) use (m/kDarkLevel) · s_{rgb·kDarkLevel/m};
//   Unbounded:   m · s_{rgb/m}(λ), m = max(rgb);
//   Illuminant:  m · s_{rgb/m}(λ) · D65(λ) / (D65's Y), so RGB (1,1,1) emits D65 with Y = 1.
// Greys (r = g = b) are exactly constant (Illuminant: exactly D65). In RGB mode every kind returns
// the triple unchanged.
#pragma once

#include "spectral/rgb_upsampling.h"
#include "spectral/spectrum.h"

namespace iris {

class RGBSpectrum final : public Spectrum {
public:
    /// Reflectances darker than this (max component) are fitted at this brightness and scaled.
    static constexpr float kDarkLevel = 0.05f;

    RGBSpectrum(const vec3& rgb, SpectrumKind kind);

    float eval(float lambda) const override;
    /// eval without the Illuminant D65 factor: eval(λ) = shapeValue(λ) · d65Factor() · D65(λ)
    /// (d65Factor() is 0 for other kinds, whose eval is shapeValue). For callers that sum several
    /// illuminant spectra and apply the D65 factor once (it is common to all of them).
    float shapeValue(float lambda) const { return scale_ * (grey_ ? level_ : poly_(lambda)); }
    float d65Factor() const { return d65Scale_; }
    /// The factor m of shapeValue (shapeValue = m · sigmoid(λ), or m · level for greys).
    float shapeScale() const { return scale_; }
    float maxValue() const override { return max_; }
    SampledSpectrum sample(const SampledWavelengths& wl) const override;
    vec3 rgbValue() const override { return rgb_; }

    /// The fitted sigmoid (unused when isGrey()).
    const SigmoidPolynomial& sigmoid() const { return poly_; }
    bool isGrey() const { return grey_; }
    /// Component error of the fit (0 for greys), in units of the normalised colour rgb/m.
    float fitError() const { return fitError_; }

private:
    vec3 rgb_;
    SigmoidPolynomial poly_;
    bool grey_ = false;
    float level_ = 0;     // grey: constant value of the shape
    float scale_ = 1;     // m
    float d65Scale_ = 0;  // Illuminant: ∫ȳ / ∫ D65 ȳ, else 0 (no D65 factor)
    float max_ = 0;
    float fitError_ = 0;
};

}  // namespace iris
