#include "materials/gltf_texture.h"

#include <cmath>

#include "core/mesh.h"

namespace iris::gltf {

vec2 TextureTransform::apply(const vec2& uv) const {
    if (identity()) return uv;
    const float c = std::cos(rotation), s = std::sin(rotation);
    const vec2 scaled = uv * scale;
    // KHR_texture_transform: rotation matrix [[cos, sin], [−sin, cos]] (row-major) applied after scale.
    return vec2(c * scaled.x + s * scaled.y, -s * scaled.x + c * scaled.y) + offset;
}

vec4 Texture::rgba(const TextureQuery& q) const {
    const vec2 uv = transform_.apply(texCoordAt(q, texCoord_));
    const Bitmap& b = *image_;
    const Bitmap::Footprint fp = b.footprint(uv, filter_, wrap_);
    vec4 out(0.0f);
    const int ch = b.channels();
    for (int i = 0; i < fp.count; ++i) {
        vec4 t(b.texel(fp.texel[i], 0));
        t.a = 1.0f;
        if (ch == 2) t.a = b.texel(fp.texel[i], 1);
        if (ch >= 3) t = vec4(b.texel(fp.texel[i], 0), b.texel(fp.texel[i], 1), b.texel(fp.texel[i], 2), 1.0f);
        if (ch >= 4) t.a = b.texel(fp.texel[i], 3);
        out += fp.weight[i] * t;
    }
    return out;
}

vec2 texCoordAt(const TextureQuery& q, int set) {
    if (set == 0) return q.uv;
    const MeshAttribute* a = q.mesh ? q.mesh->findAttribute(kTexCoord1Attribute) : nullptr;
    if (!a) return vec2(0.0f);
    return vec2(a->at(*q.mesh, q.triangle, q.bary, 0), a->at(*q.mesh, q.triangle, q.bary, 1));
}

vec4 vertexColorAt(const TextureQuery& q) {
    const MeshAttribute* a = q.mesh ? q.mesh->findAttribute(kColorAttribute) : nullptr;
    if (!a) return vec4(1.0f);
    vec4 c(1.0f);
    for (int k = 0; k < std::min(a->channels, 4); ++k) c[k] = a->at(*q.mesh, q.triangle, q.bary, k);
    return c;
}

}  // namespace iris::gltf
