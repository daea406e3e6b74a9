#include "materials/gltf_normal_map.h"

#include "core/mesh.h"
#include "materials/perturbed_frame.h"

namespace iris::gltf {

namespace {

/// The TANGENT attribute at q (xyz, w), or w = 0 when the mesh has none.
vec4 tangentAttributeAt(const TextureQuery& q) {
    const MeshAttribute* a = q.mesh ? q.mesh->findAttribute(kTangentAttribute) : nullptr;
    if (!a || a->channels != 4) return vec4(0.0f);
    vec4 t;
    for (int k = 0; k < 4; ++k) t[k] = a->at(*q.mesh, q.triangle, q.bary, k);
    return t;
}

/// v without its component along the unit vector n, normalised; nullopt when nothing is left.
std::optional<vec3> orthogonal(const vec3& v, const vec3& n) {
    const vec3 s = v - n * glm::dot(n, v);
    const float len2 = glm::dot(s, s);
    if (!(len2 > 1e-12f) || !std::isfinite(len2)) return std::nullopt;
    return s / std::sqrt(len2);
}

class NormalMapped final : public PerturbedMaterial {
public:
    NormalMapped(MaterialPtr nested, TexturePtr map, float scale)
        : PerturbedMaterial(std::const_pointer_cast<Material>(std::move(nested)), PerturbOptions{true, false}),
          map_(std::move(map)), scale_(scale) {}

    vec3 perturbation(const ShadingPoint& sp) const override { return sp.shading.toLocal(mappedNormal(sp, *map_, scale_)); }

private:
    TexturePtr map_;
    float scale_;
};

}  // namespace

TangentFrame tangentFrameAt(const ShadingPoint& sp) {
    const vec3 n = sp.shading.n;
    const vec4 attr = tangentAttributeAt(sp.tex);
    float w = attr.w < 0 ? -1.0f : 1.0f;  // §3.7.2.1: w is ±1, the handedness
    std::optional<vec3> t = attr.w != 0 ? orthogonal(vec3(attr), n) : std::nullopt;
    if (!t) {  // no (usable) TANGENT: ∂p/∂u of the triangle, bitangent N × T
        t = orthogonal(sp.dpdu, n);
        w = 1.0f;
    }
    if (!t) t = sp.shading.s;
    return {*t, glm::cross(n, *t) * w, n};  // §3.7.2.1: bitangent = cross(normal, tangent.xyz) · w
}

vec3 mappedNormal(const ShadingPoint& sp, const Texture& map, float scale) {
    const vec3 c = vec3(map.rgba(sp.tex));
    // material.normalTextureInfo.scale (schema): scaledNormal = normalize((sample · 2 − 1) · (scale, scale, 1)).
    const vec3 local = (c * 2.0f - 1.0f) * vec3(scale, scale, 1.0f);
    const TangentFrame f = tangentFrameAt(sp);
    const vec3 n = local.x * f.t + local.y * f.b + local.z * f.n;
    const float len2 = glm::dot(n, n);
    if (!(len2 > 0) || !std::isfinite(len2)) return f.n;  // a texel of (0.5, 0.5, 0.5): no direction
    return n / std::sqrt(len2);
}

MaterialPtr makeNormalMapped(MaterialPtr material, TexturePtr map, float scale) {
    return std::make_shared<NormalMapped>(std::move(material), std::move(map), scale);
}

}  // namespace iris::gltf
