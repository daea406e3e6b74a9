#include "render/instance_transform.h"

namespace iris {

InstanceTransform::InstanceTransform(const mat4& m)
    : toWorld(m), toObject(glm::inverse(m)), normalToWorld(glm::transpose(glm::inverse(mat3(m)))) {}

Ray InstanceTransform::toObjectRay(const Ray& world) const {
    return Ray(transformPoint(toObject, world.o), transformVector(toObject, world.d), world.tMax);
}

void InstanceTransform::toWorldInteraction(SurfaceInteraction& si) const {
    si.p = transformPoint(toWorld, si.p);
    // Normals transform by the inverse transpose (pbrt-v4 §3.10.3), so they stay perpendicular to
    // the transformed tangents ∂p/∂u, ∂p/∂v under non-uniform scale.
    si.ng = glm::normalize(normalToWorld * si.ng);
    si.ns = glm::normalize(normalToWorld * si.ns);
    si.dpdu = transformVector(toWorld, si.dpdu);
    si.dpdv = transformVector(toWorld, si.dpdv);
}

}  // namespace iris
