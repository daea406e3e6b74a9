// KHR_materials_iridescence's film as the glTF material reads it, per lane: the exact Airy
// reflectance at each lane's wavelength, or the extension's RGB approximation (Khr reading, RGB
// mode). Dielectric bases use the effective base F0 = specular · min(F0(ior) · specularColor, 1)
// as the README's iridescent_dielectric_layer does, turned into a real index (Fresnel0ToIor);
// metallic bases use Gulbrandsen 2014's (n, k) from the base colour and edge tint (exact) or the
// base colour as F0 (Khr). The Cycles 4.2 reading (RGB mode, dielectric bases only) is Blender's
// Principled thin film on the same base index (spectral/thin_film_cycles.h). docs/gltf.md §Thin film.
#pragma once

#include "materials/gltf_pbr_bsdf.h"

namespace iris::gltf {

/// F_film per lane at cosθ1 = |v·h| for the metallic (metal = true) or dielectric base.
SampledSpectrum thinFilmFresnel(const PbrPoint& p, float cosTheta1, bool metal);

}  // namespace iris::gltf
