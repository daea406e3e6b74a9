// Per-channel parameters of the thesis' three-channel models (thesis 000 §2.4, §3.2): the film
// index η_t is given per RGB channel together with the wavelength λ each channel stands for.
//
//   RGB mode:      channel c uses η_t[c] and λ[c] (λ from the material's `wavelengths`
//                  parameter, default defaultChannelWavelengths(), thesis Table 3.1), exactly as
//                  the thesis computes.
//   Spectral mode: each sampled wavelength λ plays the role of a channel: η_t(λ) is the
//                  piecewise-linear interpolation of the three per-channel values across the
//                  channel wavelengths (constant outside their range).
// η_t is an IOR (spectral/ior.h) read by spectral/ior_params.h with the material's channel
// wavelengths, so it takes every form of an index: a spectrum or a formula is evaluated at λ[c]
// in RGB mode and at λ in spectral mode; a preset name is a constant.
#pragma once

#include <string>

#include "core/properties.h"
#include "spectral/ior.h"
#include "spectral/ior_params.h"
#include "spectral/wavelengths.h"

namespace iris {

struct ThesisChannels {
    vec3 lambdas;           // the material's channel wavelengths (nm)
    SampledWavelengths rgb; // RGB mode's three channels at those wavelengths
    IOR etaT;               // the film index η_t

    /// Read `wavelengths` (positive, nm) and `eta_t` (default: defEtaT per channel); `model`
    /// names the plugin in error messages.
    static ThesisChannels read(const Properties& p, const char* model, const vec3& defEtaT) {
        ThesisChannels c;
        c.lambdas = p.getRGB("wavelengths", defaultChannelWavelengths());
        for (int k = 0; k < 3; ++k)
            if (!(c.lambdas[k] > 0)) failAt(p.locationOf("wavelengths"), model, ": wavelengths must be positive (nm)");
        c.rgb = SampledWavelengths::rgb(c.lambdas);
        c.etaT = readIOR(p, "eta_t", IOR::perChannel(defEtaT, c.lambdas), c.lambdas);
        return c;
    }

    /// The wavelengths a path's entries stand for: the material's channel wavelengths in RGB mode,
    /// the sampled wavelengths in spectral mode.
    const SampledWavelengths& of(const SampledWavelengths& wl) const { return wl.isRGB() ? rgb : wl; }
    /// The same as a spectrum (λ per entry, nm).
    SampledSpectrum lambdasOf(const SampledWavelengths& wl) const {
        const SampledWavelengths& c = of(wl);
        SampledSpectrum l(c.size());
        for (int k = 0; k < c.size(); ++k) l[k] = c.lambda(k);
        return l;
    }
};

}  // namespace iris
