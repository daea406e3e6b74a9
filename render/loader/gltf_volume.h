// KHR_materials_volume (Khronos extension README, "Properties", "Attenuation"): a material with
// thicknessFactor > 0 that transmits makes its mesh the boundary of a volume. The BSDF then refracts
// with the material's IOR (materials/gltf_pbr_bsdf.h); the inside is a homogeneous, purely
// absorbing medium (Beer-Lambert) with σ_a = −ln(attenuationColor) / attenuationDistance per RGB
// channel, an iris `homogeneous` medium whose RGB σ_a is upsampled in spectral mode as the XML
// scenes' RGB medium coefficients are. thicknessTexture is for rasterizers (the README: ray tracers
// use the traced distance): it is checked, not read. docs/gltf.md.
#pragma once

#include <limits>

#include "core/math.h"
#include "media/medium.h"
#include "render/loader/gltf_document.h"

namespace iris::gltf {

struct Volume {
    float thickness = 0.0f;                                             // thicknessFactor, mesh units
    float attenuationDistance = std::numeric_limits<float>::infinity();  // world units
    vec3 attenuationColor{1.0f};
};

/// The extension object `ext` at JSON path `path`: thicknessFactor >= 0, attenuationDistance > 0,
/// attenuationColor three numbers in [0, 1]; anything else is an error naming the file and path.
Volume readVolume(const Document& doc, const tinygltf::Value& ext, const std::string& path);

/// σ_a per channel in scene units: −ln(c) / (d · lengthScale) (README "Attenuation":
/// σ_t = −log(c)/d, σ_s = 0); 0 where c = 1 or d = ∞; c = 0 is taken as 1e-30 (a finite σ_a
/// after which nothing visible passes one attenuation distance).
vec3 absorptionCoefficient(const Volume& v, float lengthScale);

/// The homogeneous medium of absorption σ_a (RGB, no scattering), or nullptr when σ_a = 0.
MediumPtr absorbingMedium(const Document& doc, const vec3& sigmaA);

}  // namespace iris::gltf
