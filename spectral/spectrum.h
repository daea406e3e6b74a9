// Continuous spectra (functions of wavelength in nm) and how they are sampled at a path's
// wavelengths. In RGB mode each spectrum yields three linear Rec.709 channel values:
//   - spectra defined by an RGB triple return that triple unchanged (bit-exact thesis RGB mode);
//   - Reflectance / Illuminant spectra defined spectrally return their projection to linear
//     Rec.709 (computed once at construction by rgbProjection(), see spectral/color_space.h);
//   - Unbounded spectra (IOR, thickness, scale factors) are evaluated at the channel wavelengths.
#pragma once

#include <memory>

#include "core/math.h"
#include "spectral/sampled_spectrum.h"
#include "spectral/wavelengths.h"

namespace iris {

enum class SpectrumKind {
    Reflectance,  // dimensionless, bounded to [0, 1] (albedos, reflectances)
    Unbounded,    // dimensionless or physical, any value (IOR n and k, scale factors)
    Illuminant,   // emitted radiance (relative units, see docs/conventions.md)
};

class Spectrum {
public:
    explicit Spectrum(SpectrumKind kind) : kind_(kind) {}
    virtual ~Spectrum() = default;

    /// Spectral value at wavelength lambda (nm).
    virtual float eval(float lambda) const = 0;
    /// Upper bound of eval over [360, 830] nm.
    virtual float maxValue() const = 0;

    /// Values at the path's wavelengths (RGB mode: the channel values, see the file comment).
    virtual SampledSpectrum sample(const SampledWavelengths& wl) const {
        SampledSpectrum s(wl.size());
        if (wl.isRGB() && kind_ != SpectrumKind::Unbounded) {
            const vec3 c = rgbValue();
            for (int i = 0; i < 3; ++i) s[i] = c[i];
        } else {
            for (int i = 0; i < wl.size(); ++i) s[i] = eval(wl.lambda(i));
        }
        return s;
    }

    /// The value used in RGB mode for Reflectance and Illuminant spectra (linear Rec.709).
    virtual vec3 rgbValue() const = 0;

    SpectrumKind kind() const { return kind_; }

private:
    SpectrumKind kind_;
};

using SpectrumPtr = std::shared_ptr<const Spectrum>;

/// A constant spectrum: the same value at every wavelength and in every RGB channel.
class ConstantSpectrum final : public Spectrum {
public:
    explicit ConstantSpectrum(float c, SpectrumKind kind = SpectrumKind::Unbounded) : Spectrum(kind), c_(c) {}
    float eval(float) const override { return c_; }
    float maxValue() const override { return c_; }
    SampledSpectrum sample(const SampledWavelengths& wl) const override { return SampledSpectrum(wl.size(), c_); }
    vec3 rgbValue() const override { return vec3(c_); }
    float value() const { return c_; }

private:
    float c_;
};

}  // namespace iris
