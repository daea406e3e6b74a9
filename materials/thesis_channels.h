// Per-channel parameters of the thesis' three-channel models (thesis 000 §2.4, §3.2): the film
// index η_t is given per RGB channel together with the wavelength λ each channel stands for.
//
//   RGB mode:      channel c uses η_t[c] and λ[c] (λ from the material's `wavelengths`
//                  parameter, default 645, 525, 445 nm), exactly as the thesis computes.
//   Spectral mode: each sampled wavelength λ plays the role of a channel: η_t(λ) is the
//                  piecewise-linear interpolation of the three per-channel values across the
//                  channel wavelengths (constant outside their range).
// η_t may also be given as a spectrum: then it is evaluated at λ[c] (RGB) or at λ (spectral).
#pragma once

#include <algorithm>
#include <string>

#include "core/properties.h"
#include "spectral/channel_lerp.h"
#include "spectral/spectrum.h"
#include "spectral/spectrum_params.h"
#include "spectral/wavelengths.h"

namespace iris {

/// Default channel wavelengths of the thesis (Table 3.1, nm).
inline vec3 thesisDefaultWavelengths() { return vec3(645.0f, 525.0f, 445.0f); }

class ChannelIOR {
public:
    ChannelIOR() = default;
    /// Per-channel values at the channel wavelengths.
    ChannelIOR(const vec3& values, const vec3& lambdas) : values_(values), lambdas_(lambdas), lerp_(values, lambdas) {}
    /// A spectrum (evaluated at the channel wavelengths in RGB mode).
    ChannelIOR(SpectrumPtr s, const vec3& lambdas) : spectrum_(std::move(s)), lambdas_(lambdas) {}

    /// Read parameter `name` (rgb triple / float / vector, or any spectrum) from p.
    static ChannelIOR fromProperties(const Properties& p, const std::string& name, const vec3& def,
                                     const vec3& lambdas) {
        if (!p.has(name)) return ChannelIOR(def, lambdas);
        try {
            return ChannelIOR(p.getRGB(name, def), lambdas);
        } catch (const Error&) {
            return ChannelIOR(getSpectrum(p, name, SpectrumKind::Unbounded), lambdas);
        }
    }

    const vec3& lambdas() const { return lambdas_; }

    /// Value at wavelength λ: the spectrum, or piecewise-linear through the channel values.
    float at(float lambda) const {
        if (spectrum_) return spectrum_->eval(lambda);
        return lerp_(lambda);
    }

    /// Value of channel c in RGB mode (exactly the given triple when given per channel).
    float channel(int c) const { return spectrum_ ? spectrum_->eval(lambdas_[c]) : values_[c]; }

    /// Per-path values: RGB mode → the channel values; spectral → at(λ_k).
    SampledSpectrum sample(const SampledWavelengths& wl) const {
        SampledSpectrum s(wl.size());
        for (int k = 0; k < wl.size(); ++k) s[k] = wl.isRGB() ? channel(k) : at(wl.lambda(k));
        return s;
    }
    float maxValue() const {
        if (spectrum_) return spectrum_->maxValue();
        return std::max(values_[0], std::max(values_[1], values_[2]));
    }
    float minValue() const {
        if (spectrum_) {
            float m = spectrum_->eval(kLambdaMin);
            for (float l = kLambdaMin; l <= kLambdaMax; l += 1.0f) m = std::min(m, spectrum_->eval(l));
            return m;
        }
        return std::min(values_[0], std::min(values_[1], values_[2]));
    }

private:
    vec3 values_{1.5f};
    SpectrumPtr spectrum_;
    vec3 lambdas_ = thesisDefaultWavelengths();
    ChannelLerp lerp_{values_, lambdas_};  // the per-channel values across the channel wavelengths
};

/// The wavelength (nm) each path entry stands for: the material's channel wavelengths in RGB
/// mode, the sampled wavelengths in spectral mode.
inline SampledSpectrum channelLambdas(const SampledWavelengths& wl, const vec3& materialLambdas) {
    SampledSpectrum l(wl.size());
    for (int k = 0; k < wl.size(); ++k) l[k] = wl.isRGB() ? materialLambdas[k] : wl.lambda(k);
    return l;
}

}  // namespace iris
