// glTF materials (glTF 2.0 §3.9, the KHR_materials_* extensions) as iris materials
// (materials/gltf_pbr.h), their textures (§3.8; colour textures sRGB-decoded, §3.9.6) and their
// emission (emissiveFactor × emissiveTexture × KHR_materials_emissive_strength).
#pragma once

#include <map>
#include <memory>
#include <utility>

#include "materials/gltf_pbr.h"
#include "render/loader/gltf_document.h"
#include "spectral/spectrum.h"

namespace iris::gltf {

/// What a primitive's material gives its shape.
struct ShapeMaterial {
    MaterialPtr material;
    SpectrumPtr emission;                // constant emission, or nullptr
    SpectrumTexturePtr emissionTexture;  // textured emission (then emission is nullptr)
    bool doubleSided = false;
};

class MaterialCache {
public:
    MaterialCache(Document& doc, std::string rgbMode) : doc_(doc), rgbMode_(std::move(rgbMode)) {}
    /// Material `index` (−1: the spec's default material, §3.9.1), built once.
    const ShapeMaterial& material(int index);

private:
    ShapeMaterial build(int index);
    /// The texture of a textureInfo at JSON path `path` (nullptr when index < 0).
    TexturePtr texture(const tinygltf::TextureInfo& info, bool srgb, const std::string& path);
    TexturePtr texture(const tinygltf::Value& info, bool srgb, const std::string& path);
    TexturePtr texture(int index, int texCoord, const tinygltf::ExtensionMap& ext, bool srgb, const std::string& path);
    std::shared_ptr<const Bitmap> image(int index, bool srgb, const std::string& path);

    Document& doc_;
    std::string rgbMode_;
    std::map<int, ShapeMaterial> materials_;
    std::map<std::pair<int, bool>, std::shared_ptr<const Bitmap>> images_;
};

}  // namespace iris::gltf
