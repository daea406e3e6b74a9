// Shading-frame perturbations of the `normalmap` and `bumpmap` wrapper materials, and the
// creation of the material they wrap. Frames are world-space; `f.s` is the tangent along u.
#pragma once

#include <set>
#include <string>
#include <vector>

#include "core/frame.h"
#include "core/registry.h"
#include "materials/material.h"

namespace iris {

/// Normal mapping (Mitsuba 3 `normalmap`): the tangent-space normal nTs = (x, y, z) is expressed
/// in f (n' = normalize(x s + y t + z n)); the new tangent is f.s made orthogonal to n'
/// (Gram–Schmidt), the bitangent n' × s'. A zero nTs leaves f unchanged.
inline Frame frameFromTangentSpaceNormal(const Frame& f, const vec3& nTs) {
    const vec3 n = f.toWorld(nTs);
    const float len = glm::length(n);
    if (!(len > 0) || !isFinite(n)) return f;
    return Frame::fromNormalTangent(n / len, f.s);
}

/// Bump mapping (Blinn 1978, "Simulation of Wrinkled Surfaces"; pbrt-v4 §10.5.3; Mitsuba 3
/// `bumpmap`): the surface is displaced along n by the height h(u, v), so with
/// g = (∂h/∂u, ∂h/∂v) (already multiplied by the bump scale) and the terms in ∂n/∂u dropped,
///   ∂p'/∂u = ∂p/∂u + g.x n,  ∂p'/∂v = ∂p/∂v + g.y n,  n' = normalize(∂p'/∂u × ∂p'/∂v).
/// Only ∂p/∂u is known at a shading point, so ∂p/∂v is taken as |∂p/∂u| t (an orthogonal uv
/// parametrisation with equal scale in u and v — exact for square-mapped planar patches).
/// Then n' ∝ n − (g.x/L) s − (g.y/L) t with L = |∂p/∂u| (1 if unknown): the normal tilts by
/// atan(|g|/L) away from the uphill direction. The tangent is ∂p'/∂u made orthogonal to n'.
inline Frame frameFromHeightGradient(const Frame& f, const vec3& dpdu, const vec2& g) {
    float l = glm::length(dpdu);
    if (!(l > 0) || !std::isfinite(l)) l = 1.0f;
    const vec3 dpduB = l * f.s + g.x * f.n;
    const vec3 dpdvB = l * f.t + g.y * f.n;
    vec3 n = glm::cross(dpduB, dpdvB);
    const float len = glm::length(n);
    if (!(len > 0) || !isFinite(n)) return f;
    n /= len;
    return Frame::fromNormalTangent(n, dpduB);
}

/// The nested object under parameter `name` of a wrapper; any other value there is an unknown
/// parameter of the wrapper (error naming it and the known ones).
inline PropertiesPtr nestedObjectOrFail(const Properties& p, const std::string& name, const std::string& plugin,
                                        const std::set<std::string>& ownParams) {
    try {
        return p.getObject(name);
    } catch (const Error&) {
        std::string known;
        for (const auto& k : ownParams) known += (known.empty() ? "" : ", ") + k;
        failAt(p.locationOf(name), "unknown parameter '", name, "' of bsdf '", plugin, "' (known parameters: ", known,
               ", and nested objects)");
    }
}

/// The one material nested in a wrapper `plugin` (Mitsuba style: an unnamed <bsdf> child, or a
/// <bsdf> under any parameter name not listed in `ownParams`); cached in the child's
/// Properties::instance like every other scene object. Errors name the wrapper's location.
inline std::shared_ptr<Material> createNestedMaterial(const Properties& p, const std::string& plugin,
                                                     const std::set<std::string>& ownParams) {
    std::vector<PropertiesPtr> nested;
    for (const PropertiesPtr& c : p.children())
        if (c->tag() == "bsdf") nested.push_back(c);
    for (const std::string& name : p.names()) {
        if (ownParams.count(name)) continue;
        const PropertiesPtr obj = nestedObjectOrFail(p, name, plugin, ownParams);
        if (obj->tag() == "bsdf") nested.push_back(obj);
    }
    if (nested.size() != 1)
        failAt(p.location(), plugin, ": expected exactly one nested bsdf, got ", nested.size());
    const PropertiesPtr& child = nested[0];
    if (child->instance) return std::static_pointer_cast<Material>(child->instance);
    auto m = MaterialRegistry::instance().create(*child);
    child->instance = m;
    return m;
}

}  // namespace iris
