// An instance's placement (render/scene.cpp): the surface interaction of a shape of a shape group,
// computed in the group's space, carried to world space as Mitsuba 3's Instance does
// (src/shapes/instance.cpp, compute_surface_interaction): points and the tangents ∂p/∂u, ∂p/∂v by
// to_world, normals by its inverse transpose (then renormalised); uv, t and dpScale unchanged.
#pragma once

#include "core/math.h"
#include "core/ray.h"

namespace iris {

struct InstanceTransform {
    mat4 toWorld{1.0f};
    mat4 toObject{1.0f};  // the inverse of toWorld
    mat3 normalToWorld{1.0f};  // normalMatrix(toWorld)

    explicit InstanceTransform(const mat4& m);
    /// The world ray in the group's space (same t along it: the direction is not renormalised).
    Ray toObjectRay(const Ray& world) const;
    /// p, ng, ns, dpdu and dpdv of `si` from the group's space to world space.
    void toWorldInteraction(SurfaceInteraction& si) const;
};

}  // namespace iris
