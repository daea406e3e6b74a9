#include "render/instance_transform.h"

namespace iris {

InstanceTransform::InstanceTransform(const mat4& m)
    : toWorld(m), toObject(glm::inverse(m)), normalToWorld(normalMatrix(m)) {}

Ray InstanceTransform::toObjectRay(const Ray& world) const {
    return Ray(transformPoint(toObject, world.o), transformVector(toObject, world.d), world.tMax);
}

void InstanceTransform::toWorldInteraction(SurfaceInteraction& si) const {
    si.p = transformPoint(toWorld, si.p);
    // Normals by the inverse transpose (core/math.h normalMatrix), renormalised.
    si.ng = glm::normalize(normalToWorld * si.ng);
    si.ns = glm::normalize(normalToWorld * si.ns);
    si.dpdu = transformVector(toWorld, si.dpdu);
    si.dpdv = transformVector(toWorld, si.dpdv);
}

}  // namespace iris
