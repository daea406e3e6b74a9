// Small scenes built in code for renderer tests (no scene file needed).
#pragma once

#include "render/lights/light.h"
#include "core/properties.h"
#include "core/registry.h"
#include "render/scene_description.h"
#include "materials/material.h"

namespace iris::testing {

inline MaterialPtr makeDiffuse(float albedo) {
    Properties p("bsdf", "diffuse", SourceLocation{"<test>", 0});
    p.set("reflectance", albedo, SourceLocation{"<test>", 0});
    return MaterialRegistry::instance().create(p);
}

inline LightPtr makeConstantEnvironment(float radiance) {
    Properties p("emitter", "constant", SourceLocation{"<test>", 0});
    p.set("radiance", radiance, SourceLocation{"<test>", 0});
    return LightRegistry::instance().create(p);
}

/// A unit sphere of the given albedo seen from z = −4 filling the central pixels, inside a
/// uniform environment of radiance 1 (the white furnace).
inline SceneDescription furnaceScene(float albedo, int res = 16, int spp = 64) {
    SceneDescription d;
    d.sourceFile = "<furnace>";
    ShapeDescription s;
    s.type = ShapeDescription::Type::Sphere;
    s.center = vec3(0.0f);
    s.radius = 1.0f;
    s.material = makeDiffuse(albedo);
    s.name = "sphere";
    d.shapes.push_back(s);
    d.lights.push_back(makeConstantEnvironment(1.0f));
    d.camera.toWorld = glm::inverse(glm::lookAt(vec3(0, 0, -4), vec3(0.0f), vec3(0, 1, 0)));
    // glm::lookAt looks along −z; Mitsuba cameras look along +z: flip x and z.
    d.camera.toWorld = d.camera.toWorld * glm::scale(mat4(1.0f), vec3(-1, 1, -1));
    d.camera.fovDegrees = 40.0f;
    d.camera.width = d.camera.height = res;
    d.camera.filter = CameraDescription::Filter::Box;
    d.integrator.type = "path";
    d.integrator.maxDepth = -1;
    d.spp = spp;
    return d;
}

}  // namespace iris::testing
