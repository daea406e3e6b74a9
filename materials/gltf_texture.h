// A glTF texture as a material reads it (glTF 2.0 §3.8 "Textures", §3.9.x textureInfo): an image
// with its sampler's filter and wrap modes, the texture coordinate set it uses (TEXCOORD_n) and
// KHR_texture_transform's offset, rotation and scale. Lookups return the four channels RGBA as
// stored after the colour decoding the loader chose (sRGB → linear for colour textures, §3.9.6).
#pragma once

#include <memory>

#include "core/math.h"
#include "materials/textures/bitmap.h"
#include "materials/textures/texture.h"

namespace iris::gltf {

/// The name of the mesh attribute that holds the second texture coordinate set (TEXCOORD_1).
constexpr const char* kTexCoord1Attribute = "vertex_texcoord1";
/// The mesh attribute of the vertex colour COLOR_0 (RGB or RGBA).
constexpr const char* kColorAttribute = "vertex_color";
/// The mesh attribute of the vertex tangents TANGENT (xyz and the bitangent sign w).
constexpr const char* kTangentAttribute = "vertex_tangent";

struct TextureTransform {
    vec2 offset{0.0f}, scale{1.0f};
    float rotation = 0.0f;
    /// KHR_texture_transform: uv' = T(offset) · R(rotation) · S(scale) · uv, with
    /// R = [[cos, sin], [−sin, cos]] (the extension's README, "Transform").
    vec2 apply(const vec2& uv) const;
    bool identity() const { return offset == vec2(0.0f) && scale == vec2(1.0f) && rotation == 0.0f; }
};

class Texture {
public:
    Texture(std::shared_ptr<const Bitmap> image, Bitmap::Filter filter, Bitmap::Wrap wrap, int texCoord,
            const TextureTransform& transform)
        : image_(std::move(image)), filter_(filter), wrap_(wrap), texCoord_(texCoord), transform_(transform) {}

    /// RGBA at the query's texture coordinates (missing channels: grey replicated, alpha 1).
    vec4 rgba(const TextureQuery& q) const;
    int texCoord() const { return texCoord_; }

private:
    std::shared_ptr<const Bitmap> image_;
    Bitmap::Filter filter_;
    Bitmap::Wrap wrap_;
    int texCoord_;
    TextureTransform transform_;
};

using TexturePtr = std::shared_ptr<const Texture>;

/// The uv of set `set` at q: set 0 is the hit's uv, set 1 the mesh attribute kTexCoord1Attribute
/// (0 where the mesh has none).
vec2 texCoordAt(const TextureQuery& q, int set);

/// The vertex colour COLOR_0 at q (RGBA; white where the mesh has none).
vec4 vertexColorAt(const TextureQuery& q);

}  // namespace iris::gltf
