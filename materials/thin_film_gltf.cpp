#include "materials/thin_film_gltf.h"

#include <algorithm>

#include "spectral/thin_film_cycles.h"
#include "spectral/thin_film_industry.h"

namespace iris::gltf {

namespace {

/// The dielectric base's effective F0 of lane i (KHR_materials_iridescence with
/// KHR_materials_specular: specular_weight · min(((1 − ior)/(1 + ior))² · f0_color, 1)).
double dielectricBaseF0(const PbrPoint& p, float specularColor) {
    const double f0 = iorToFresnel0(p.ior, 1.0);
    return p.specular * std::min(f0 * specularColor, 1.0);
}

}  // namespace

SampledSpectrum thinFilmFresnel(const PbrPoint& p, float cosTheta1, bool metal) {
    const int n = p.base.size();
    SampledSpectrum F(n);
    if (p.rgb && p.mode == ThinFilmRGBMode::Khr) {
        dvec3 f0;
        for (int c = 0; c < 3; ++c) f0[c] = metal ? double(p.baseRGB[c]) : dielectricBaseF0(p, p.specularColorRGB[c]);
        const dvec3 rgb = khrIridescentFresnel(1.0, p.filmIor, f0, p.thicknessNm, cosTheta1);
        for (int c = 0; c < 3; ++c) F[c] = float(rgb[c]);
        return F;
    }
    if (p.rgb && p.mode == ThinFilmRGBMode::Cycles42 && !metal) {
        // Cycles 4.2's film on the dielectric base (spectral/thin_film_cycles.h), with the base index
        // recovered from this channel's effective F0 as the exact reading recovers it.
        for (int c = 0; c < 3; ++c) {
            const double baseIor = fresnel0ToIor(std::min(dielectricBaseF0(p, p.specularColor[c]), 0.9999));
            F[c] = float(cyclesThinFilmRGB(1.0, p.filmIor, baseIor, cosTheta1, p.thicknessNm)[c]);
        }
        return F;
    }
    for (int i = 0; i < n; ++i) {
        complexd substrate;
        if (metal) {
            const double r = p.base[i];
            substrate = gulbrandsenIor(r, p.edgeTint >= 0 ? p.edgeTint : r);
        } else {
            substrate = complexd(fresnel0ToIor(std::min(dielectricBaseF0(p, p.specularColor[i]), 0.9999)), 0.0);
        }
        F[i] = float(exactThinFilmReflectance(p.lambda[i], cosTheta1, 1.0, p.filmIor, p.thicknessNm, substrate));
    }
    return F;
}

}  // namespace iris::gltf
