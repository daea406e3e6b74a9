// Small scenes built in code for renderer tests (no scene file needed).
#pragma once

#include "render/lights/light.h"
#include "core/properties.h"
#include "core/registry.h"
#include "render/integrator.h"
#include "render/scene_description.h"
#include "render/sensors/perspective.h"
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

/// A path or direct integrator with the given max_depth (−1: unlimited).
inline IntegratorPtr makeIntegrator(const std::string& type, int maxDepth) {
    Properties p("integrator", type, SourceLocation{"<test>", 0});
    p.set("max_depth", int64_t(maxDepth), SourceLocation{"<test>", 0});
    return IntegratorRegistry::instance().create(p);
}

/// A perspective camera of fov_axis x bound to a width × height film with a box filter.
inline void setCamera(CameraDescription& c, const mat4& toWorld, float fovDegrees, int width, int height) {
    c.width = width;
    c.height = height;
    c.sensor = std::make_shared<PerspectiveSensor>(toWorld, fovDegrees, FovAxis::X, FilmSize{width, height});
    c.filter = makeFilter("box");
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
    // glm::lookAt looks along −z; Mitsuba cameras look along +z: flip x and z.
    const mat4 toWorld = glm::inverse(glm::lookAt(vec3(0, 0, -4), vec3(0.0f), vec3(0, 1, 0))) * glm::scale(mat4(1.0f), vec3(-1, 1, -1));
    setCamera(d.camera, toWorld, 40.0f, res, res);
    d.integrator = makeIntegrator("path", -1);
    d.spp = spp;
    return d;
}

}  // namespace iris::testing
