// The one representation of an index of refraction, for every material: η(λ) of a medium, or an
// extinction coefficient κ(λ) (a complex index η + iκ is two IOR objects). Its forms:
//   constant      η
//   per channel   (η_R, η_G, η_B) at channel wavelengths (λ_R, λ_G, λ_B) nm (default
//                 defaultChannelWavelengths(), spectral/wavelengths.h): RGB mode returns the three
//                 values exactly; spectral mode interpolates piecewise-linearly across the channel
//                 wavelengths, constant outside (spectral/channel_lerp.h; thesis 000 §2.4 / §3.2)
//   tabulated     a spectrum, e.g. measured η(λ) or κ(λ) (spectral/data/ior/*.spd)
//   Cauchy        η = A + B/λ² (λ in µm, B in µm²; Cauchy 1836, see Born & Wolf, Principles of
//                 Optics, §2.3.4)
//   Sellmeier     η² = 1 + Σ_{i=1..3} B_i λ²/(λ² − C_i) (λ in µm, C_i in µm²; Sellmeier 1871, the
//                 form of the Schott glass catalogue's coefficients)
// A named material (Mitsuba 3's dielectric presets, spectral/ior_presets.h) is a constant. Scene
// parameters are read by spectral/ior_params.h; docs/materials.md, "Indices of refraction".
#pragma once

#include "spectral/channel_lerp.h"
#include "spectral/sampled_spectrum.h"
#include "spectral/spectrum.h"
#include "spectral/wavelengths.h"

namespace iris {

class IOR {
public:
    enum class Kind { Constant, PerChannel, Tabulated, Cauchy, Sellmeier };

    IOR() = default;  // constant 1 (vacuum)
    static IOR constant(float eta);
    /// Per-channel values at the channel wavelengths (nm); three equal values are a constant.
    static IOR perChannel(const vec3& eta, const vec3& lambdas = defaultChannelWavelengths());
    static IOR tabulated(SpectrumPtr spectrum);
    static IOR cauchy(float a, float bUm2);
    static IOR sellmeier(const vec3& b, const vec3& cUm2);

    Kind kind() const { return kind_; }

    /// The value at one wavelength (nm).
    float eval(float lambda) const {
        switch (kind_) {
            case Kind::Constant: return c_;
            case Kind::PerChannel: return lerp_(lambda);
            case Kind::Tabulated: return spectrum_->eval(lambda);
            case Kind::Cauchy: {
                const float l = lambda * 1e-3f;  // µm
                return a_.x + a_.y / (l * l);    // Cauchy: η = A + B/λ²
            }
            case Kind::Sellmeier: {
                const float l2 = sqr(lambda * 1e-3f);  // µm²
                float n2 = 1.0f;                       // Sellmeier: η² = 1 + Σ B_i λ²/(λ² − C_i)
                for (int i = 0; i < 3; ++i) n2 += a_[i] * l2 / (l2 - b_[i]);
                return safeSqrt(n2);
            }
        }
        return c_;
    }

    /// The values at a path's wavelengths. Spectral mode: eval at each. RGB mode: a per-channel
    /// triple returns its three values exactly; a spectrum follows its own RGB-mode rule
    /// (spectral/spectrum.h: an unbounded spectrum is evaluated at the channel wavelengths wl
    /// carries); the formulas are evaluated at the channel wavelengths.
    SampledSpectrum sample(const SampledWavelengths& wl) const;
    /// Entry k of sample(wl), without building the whole spectrum (for per-channel loops).
    float at(const SampledWavelengths& wl, int k) const {
        if (wl.isRGB()) {
            if (kind_ == Kind::PerChannel) return a_[k];
            if (kind_ == Kind::Tabulated) return spectrum_->sample(wl)[k];
        }
        return eval(wl.lambda(k));
    }

    /// True when the value varies with wavelength (or between RGB channels).
    bool isDispersive() const;

    /// Smallest and largest value (over [kLambdaMin, kLambdaMax] in 1 nm steps, the channel
    /// values of a triple; for a spectrum the largest is its Spectrum::maxValue bound).
    struct Range {
        float min, max;
    };
    Range range() const;

    /// Calls f(λ, value) for the values the index takes: a constant's value (λ = kLambdaMin), a
    /// triple's three channel values (at their channel wavelengths; interpolation stays between
    /// them), otherwise eval every 1 nm over [kLambdaMin, kLambdaMax]. For checks at load time.
    template <typename F>
    void forEachValue(F&& f) const {
        if (kind_ == Kind::Constant) {
            f(kLambdaMin, c_);
        } else if (kind_ == Kind::PerChannel) {
            for (int c = 0; c < 3; ++c) f(b_[c], a_[c]);
        } else {
            for (float l = kLambdaMin; l <= kLambdaMax; l += 1.0f) f(l, eval(l));
        }
    }

private:
    Kind kind_ = Kind::Constant;
    float c_ = 1.0f;
    vec3 a_{0.0f}, b_{0.0f};  // per channel: values, λ; Cauchy: (A, B, 0); Sellmeier: B, C
    ChannelLerp lerp_;        // per channel: the values across the channel wavelengths
    SpectrumPtr spectrum_;
};

/// The relative index η_int/η_ext of a dielectric interface at the path's wavelengths, written
/// to *eta. When it varies with λ in spectral mode the secondary wavelengths are terminated
/// (wl.terminateSecondary(), pbrt-v4 §9.5.2). Returns the η that decides refracted directions:
/// the hero wavelength's (index 0) in spectral mode, the green channel's (index 1) in RGB mode.
float relativeIOR(const IOR& intIOR, const IOR& extIOR, SampledWavelengths& wl, SampledSpectrum* eta);

}  // namespace iris
