// glTF materials (glTF 2.0 §3.9, the KHR_materials_* extensions) as iris materials
// (materials/gltf_pbr.h), their textures (§3.8; colour textures sRGB-decoded, §3.9.6) and their
// emission (emissiveFactor × emissiveTexture × KHR_materials_emissive_strength), its normal texture
// (materials/gltf_normal_map.h) and KHR_materials_volume's interior medium (gltf_volume.h).
#pragma once

#include <map>
#include <memory>
#include <utility>

#include "materials/gltf_pbr.h"
#include "media/medium.h"
#include "render/loader/gltf_document.h"
#include "spectral/spectrum.h"

namespace iris::gltf {

/// What a primitive's material gives its shape.
struct ShapeMaterial {
    MaterialPtr material;
    SpectrumPtr emission;                // constant emission, or nullptr
    SpectrumTexturePtr emissionTexture;  // textured emission (then emission is nullptr)
    bool doubleSided = false;
    bool normalMapped = false;  // has a normalTexture (which reads the TANGENT attribute, generated when the file has none)
    int normalTexCoord = 0;     // the normalTexture's UV set (its texCoord), for generated tangents
    MediumPtr interior;         // KHR_materials_volume's absorbing medium, or nullptr
};

class MaterialCache {
public:
    /// `lengthScale`: how long one glTF world unit is in the scene (1 for a whole-file scene; the
    /// XML shape's to_world scale), for the volume's attenuationDistance.
    MaterialCache(Document& doc, std::string rgbMode, float lengthScale = 1.0f)
        : doc_(doc), rgbMode_(std::move(rgbMode)), lengthScale_(lengthScale) {}
    /// Material `index` (−1: the spec's default material, §3.9.1), built once.
    const ShapeMaterial& material(int index);

private:
    ShapeMaterial build(int index);
    /// The texture of a textureInfo at JSON path `path` (nullptr when index < 0).
    TexturePtr texture(const tinygltf::TextureInfo& info, bool srgb, const std::string& path);
    TexturePtr texture(const tinygltf::Value& info, bool srgb, const std::string& path);
    TexturePtr texture(int index, int texCoord, const tinygltf::ExtensionMap& ext, bool srgb, const std::string& path);
    /// Checks a textureInfo's index and texCoord and its texture's image and sampler indices (no
    /// image is read); returns the texture.
    const tinygltf::Texture& checkTexture(int index, int texCoord, const std::string& path);
    std::shared_ptr<const Bitmap> image(int index, bool srgb, const std::string& path);

    Document& doc_;
    std::string rgbMode_;
    float lengthScale_;
    std::map<int, ShapeMaterial> materials_;
    std::map<std::pair<int, bool>, std::shared_ptr<const Bitmap>> images_;
};

}  // namespace iris::gltf
