// Rays and the surface interaction record returned by scene intersection.
#pragma once

#include <limits>

#include "core/frame.h"
#include "core/math.h"

namespace iris {

class Material;
class Light;
struct TriangleMesh;

struct Ray {
    vec3 o{0.0f}, d{0, 0, 1};
    float tMax = std::numeric_limits<float>::infinity();
    Ray() = default;
    Ray(const vec3& o_, const vec3& d_, float tMax_ = std::numeric_limits<float>::infinity()) : o(o_), d(d_), tMax(tMax_) {}
    vec3 at(float t) const { return o + t * d; }
};

/// Offset a ray origin off a surface along the geometric normal, to the side of `w`, by an amount
/// that scales with the coordinates' magnitude (float spacing), avoiding self-intersection.
inline vec3 offsetRayOrigin(const vec3& p, const vec3& ng, const vec3& w) {
    const float scale = 1.0f + std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)});
    const vec3 offset = ng * (2e-5f * scale);
    return glm::dot(w, ng) >= 0 ? p + offset : p - offset;
}

struct SurfaceInteraction {
    vec3 p{0.0f};        // hit point (world)
    float t = 0.0f;      // ray distance
    vec3 ng{0, 0, 1};    // geometric normal (world, unit; oriented by the shape's winding / outside)
    vec3 ns{0, 0, 1};    // interpolated shading normal (world, unit)
    // The surface derivatives are dpScale·dpdu = ∂p/∂u and dpScale·dpdv = ∂p/∂v (meshes: from the
    // triangle's uvs, dpScale = 1; spheres: Scene::intersect). dpdu also gives the shading frame's
    // tangent; spheres store both divided by 2πr, so that frame is bit for bit that of earlier
    // versions. Bump mapping needs the derivatives with their lengths.
    vec3 dpdu{1, 0, 0};
    vec3 dpdv{0, 1, 0};
    float dpScale = 1.0f;
    vec2 uv{0.0f};
    vec3 wo{0.0f};       // direction towards the ray origin
    int shapeIndex = -1;
    // Triangle meshes: the mesh, the triangle and the hit's barycentrics (b1, b2) (for mesh attributes).
    const TriangleMesh* mesh = nullptr;
    uint32_t triangle = 0;
    vec2 bary{0.0f};
    const Material* material = nullptr;
    const Light* areaLight = nullptr;

    Ray spawnRay(const vec3& d) const { return Ray(offsetRayOrigin(p, ng, d), d); }
};

}  // namespace iris
