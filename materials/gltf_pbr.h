// The glTF 2.0 material (glTF 2.0 §3.9 and Appendix B "BRDF Implementation") with the Khronos
// extensions KHR_materials_ior, _specular, _transmission, _volume (the boundary; its medium is the
// shape's), _clearcoat, _sheen, _iridescence and _emissive_strength (emission is the shape's, render/loader/gltf_*). The glTF loader builds it
// from a file's material; the plugin "gltf_pbr" builds it from scene-file parameters (constants
// only), so BRDF-level experiments and tests reach it through iris.Material. docs/gltf.md.
#pragma once

#include <string>

#include "core/math.h"
#include "core/properties.h"
#include "materials/gltf_texture.h"
#include "materials/material.h"

namespace iris::gltf {

/// How a thin film (KHR_materials_iridescence) is evaluated. Exact: the Airy reflectance at each
/// wavelength (spectral mode) or at each channel wavelength (RGB mode), metals as complex indices
/// by Gulbrandsen 2014 from the base colour and edge tint. Khr: the extension's own RGB
/// approximation (spectral/thin_film_industry.h), only in RGB mode.
enum class ThinFilmRGBMode { Exact, Khr, Cycles42 };
/// The `rgb_mode` names: "point" (Exact) and "khr_iridescence" (Khr). Throws iris::Error otherwise.
ThinFilmRGBMode parseThinFilmRGBMode(const std::string& name);

enum class AlphaMode { Opaque, Mask, Blend };

/// A factor times one channel of an optional texture (glTF's factor × texture pairs).
struct ScalarInput {
    float factor = 1.0f;
    TexturePtr texture;
    int channel = 0;  // R = 0, G = 1, B = 2, A = 3
    float at(const TextureQuery& q) const { return texture ? factor * texture->rgba(q)[channel] : factor; }
};
/// An RGB factor times an optional texture's RGB (linear values).
struct ColorInput {
    vec3 factor{1.0f};
    TexturePtr texture;
    vec3 at(const TextureQuery& q) const { return texture ? factor * vec3(texture->rgba(q)) : factor; }
};

struct PbrParams {
    // Core (§3.9.2): base colour × texture × COLOR_0, metallic (B) and roughness (G).
    ColorInput baseColor;
    ScalarInput baseAlpha;  // channel 3 of the base colour texture
    ScalarInput metallic{1.0f, nullptr, 2}, roughness{1.0f, nullptr, 1};
    AlphaMode alphaMode = AlphaMode::Opaque;
    float alphaCutoff = 0.5f;
    // KHR_materials_ior, KHR_materials_specular (specular: A channel; colour: RGB).
    float ior = 1.5f;
    ScalarInput specular{1.0f, nullptr, 3};
    ColorInput specularColor;
    // KHR_materials_transmission (R), KHR_materials_clearcoat (R; roughness G).
    ScalarInput transmission{0.0f, nullptr, 0};
    ScalarInput clearcoat{0.0f, nullptr, 0}, clearcoatRoughness{0.0f, nullptr, 1};
    // KHR_materials_sheen (colour RGB; roughness A).
    ColorInput sheenColor{vec3(0.0f), nullptr};
    ScalarInput sheenRoughness{0.0f, nullptr, 3};
    // KHR_materials_iridescence (intensity R; thickness G maps [0, 1] to [min, max] nm).
    ScalarInput iridescence{0.0f, nullptr, 0};
    float iridescenceIor = 1.3f, thicknessMin = 100.0f, thicknessMax = 400.0f;
    TexturePtr thicknessTexture;
    /// Gulbrandsen's edge tint g of a metallic base under a film; negative: the base colour.
    float edgeTint = -1.0f;
    ThinFilmRGBMode rgbMode = ThinFilmRGBMode::Exact;
    bool vertexColor = true;  // multiply COLOR_0 of the mesh into the base colour
    /// glTF's doubleSided (§3.9.5): lit from both sides. A single-sided material is culled from
    /// behind, as rasterizers cull back faces: light passes through it unchanged.
    bool doubleSided = false;
    /// KHR_materials_volume with thicknessFactor > 0: the surface bounds a volume. Transmission
    /// refracts with `ior` (the extension's refractive microfacet BTDF) instead of passing
    /// thin-walled, and the back side is the interface seen from inside (doubleSided has no
    /// effect). The medium inside is the shape's (render/loader/gltf_volume.h).
    bool volume = false;
};

/// The material of `params` (no validation: the loader and the plugin check their inputs).
MaterialPtr makePbrMaterial(PbrParams params);

}  // namespace iris::gltf
