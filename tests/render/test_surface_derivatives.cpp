// ∂p/∂u and ∂p/∂v of the surface interaction (what `bumpmap` needs, with their lengths): from
// a triangle mesh's uvs (a rectangle stretched to a non-square uv mapping) and from the analytic
// sphere's parametrisation (Mitsuba 3: u = φ/2π, v = θ/π); both checked against finite
// differences of the hit point over uv; a rotated sphere's uv and tangents turn with its to_world
// (Mitsuba 3 computes them in object space), also for the uv of its emitter's light samples.
#include <gtest/gtest.h>

#include "core/ray.h"
#include "render/lights/light.h"
#include "render/loader/scene_loader.h"
#include "render/scene.h"

namespace iris {
namespace {

void expectVecNear(const vec3& a, const vec3& b, float tol, const char* what) {
    EXPECT_NEAR(a.x, b.x, tol) << what;
    EXPECT_NEAR(a.y, b.y, tol) << what;
    EXPECT_NEAR(a.z, b.z, tol) << what;
}

TEST(SurfaceDerivatives, MeshWithNonSquareUVScaling) {
    // Mitsuba's rectangle [-1, 1]² with uv [0, 1]², scaled by 4 in x and 1 in y: ∂p/∂u has length
    // 8, ∂p/∂v length 2, and they are perpendicular; a hit gives both, with their lengths.
    const std::string xml = R"(<scene version="3.0.0">
  <shape type="rectangle">
    <transform name="to_world"><scale x="4" y="1" z="1"/></transform>
  </shape>
</scene>)";
    Scene scene(loadSceneFromString(xml, "."));
    auto hitAt = [&](float x, float y) {
        const auto h = scene.intersect(Ray(vec3(x, y, 5.0f), vec3(0, 0, -1)));
        EXPECT_TRUE(h.has_value());
        return *h;
    };
    const SurfaceInteraction a = hitAt(0.3f, -0.2f);
    EXPECT_EQ(a.dpScale, 1.0f);
    EXPECT_NEAR(glm::length(a.dpdu), 8.0f, 1e-4f);
    EXPECT_NEAR(glm::length(a.dpdv), 2.0f, 1e-4f);
    EXPECT_NEAR(glm::dot(a.dpdu, a.dpdv), 0.0f, 1e-4f);
    EXPECT_GT(glm::length(a.dpdu - a.dpdv), 1.0f);  // not the old ∂p/∂v = |∂p/∂u| t shortcut
    // Against the uv of nearby hits: p(x + dx) − p(x) = ∂p/∂u Δu + ∂p/∂v Δv.
    const SurfaceInteraction b = hitAt(0.5f, -0.2f), c = hitAt(0.3f, 0.1f);
    expectVecNear(b.p - a.p, a.dpdu * (b.uv.x - a.uv.x) + a.dpdv * (b.uv.y - a.uv.y), 1e-4f, "x step");
    expectVecNear(c.p - a.p, a.dpdu * (c.uv.x - a.uv.x) + a.dpdv * (c.uv.y - a.uv.y), 1e-4f, "y step");
}

TEST(SurfaceDerivatives, AnalyticSphere) {
    // Radius 2: |∂p/∂u| = 2π r sin θ, |∂p/∂v| = π r; checked against the hit points of rays
    // whose uv differ slightly.
    const std::string xml = R"(<scene version="3.0.0">
  <shape type="sphere"><point name="center" x="1" y="0" z="0"/><float name="radius" value="2"/></shape>
</scene>)";
    Scene scene(loadSceneFromString(xml, "."));
    const vec3 o(1.0f, 0.0f, 0.0f);
    const float r = 2.0f;
    auto hitDir = [&](float theta, float phi) {
        const vec3 d(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
        const auto h = scene.intersect(Ray(o + 10.0f * d, -d));
        EXPECT_TRUE(h.has_value());
        return *h;
    };
    const float theta = 1.1f, phi = 0.7f;
    SurfaceInteraction a = hitDir(theta, phi);
    a.dpdu *= a.dpScale;  // the true derivatives
    a.dpdv *= a.dpScale;
    EXPECT_NEAR(a.uv.x, phi / (2 * kPi), 1e-5f);
    EXPECT_NEAR(a.uv.y, theta / kPi, 1e-5f);
    EXPECT_NEAR(glm::length(a.dpdu), 2 * kPi * r * std::sin(theta), 1e-3f);
    EXPECT_NEAR(glm::length(a.dpdv), kPi * r, 1e-3f);
    EXPECT_NEAR(glm::dot(a.dpdu, a.dpdv), 0.0f, 1e-3f);
    const float h = 1e-3f;
    const SurfaceInteraction du = hitDir(theta, phi + h), dv = hitDir(theta + h, phi);
    expectVecNear((du.p - a.p) / (du.uv.x - a.uv.x), a.dpdu, 2e-2f, "u step");
    expectVecNear((dv.p - a.p) / (dv.uv.y - a.uv.y), a.dpdv, 2e-2f, "v step");
    // ∂p/∂u × ∂p/∂v points inwards for this parametrisation (as in Mitsuba; bumpmap turns its
    // normal to the geometric normal's side).
    EXPECT_LT(glm::dot(glm::cross(a.dpdu, a.dpdv), a.ng), 0.0f);
    // The poles have finite tangents.
    const SurfaceInteraction pole = hitDir(0.0f, 0.0f);
    EXPECT_TRUE(isFinite(pole.dpdu) && isFinite(pole.dpdv));
    EXPECT_GT(glm::length(glm::cross(pole.dpdu, pole.dpdv)), 0.0f);
}

TEST(SurfaceDerivatives, ARotatedSpheresUvTurnsWithIt) {
    // to_world rotates 90° about z (object x → world y) and about x, then scales by 2 and moves:
    // the world point c + r R q has the uv the unrotated sphere has at c + r q.
    const std::string rotated = R"(<scene version="3.0.0"><shape type="sphere">
  <transform name="to_world"><rotate z="1" angle="90"/><rotate x="1" angle="30"/><scale value="2"/><translate x="1" y="-1"/></transform>
  <emitter type="area"><texture name="radiance" type="checkerboard"/></emitter></shape></scene>)";
    const std::string plain = R"(<scene version="3.0.0"><shape type="sphere"><float name="radius" value="2"/></shape></scene>)";
    Scene rs(loadSceneFromString(rotated, ".")), ps(loadSceneFromString(plain, "."));
    const mat3 R = mat3(glm::rotate(mat4(1.0f), glm::radians(30.0f), vec3(1, 0, 0)) *
                        glm::rotate(mat4(1.0f), glm::radians(90.0f), vec3(0, 0, 1)));
    const vec3 c(1.0f, -1.0f, 0.0f);
    for (const vec3 q : {vec3(0.48f, 0.36f, 0.8f), vec3(0.0f, 0.6f, -0.8f), vec3(-0.48f, 0.6f, 0.64f)}) {
        const auto a = rs.intersect(Ray(c + 10.0f * (R * q), -(R * q)));
        const auto b = ps.intersect(Ray(10.0f * q, -q));
        ASSERT_TRUE(a && b);
        EXPECT_NEAR(a->uv.x, b->uv.x, 1e-5f);
        EXPECT_NEAR(a->uv.y, b->uv.y, 1e-5f);
        expectVecNear(a->dpdu, R * b->dpdu, 1e-4f, "dp/du turns with the sphere");
        expectVecNear(a->dpdv, R * b->dpdv, 1e-4f, "dp/dv turns with the sphere");
        // The emitter's sample towards that point carries the same uv (textured radiance).
        const vec3 from = c + 5.0f * (R * q);
        const Light& light = *rs.lights().at(0);
        for (float u = 0.05f; u < 1.0f; u += 0.3f) {
            const auto ls = light.sampleLi(from, vec2(u, 0.4f), SampledWavelengths::rgb(defaultChannelWavelengths()));
            if (!ls) continue;
            const auto hit = rs.intersect(Ray(from, ls->wi));
            ASSERT_TRUE(hit.has_value());
            EXPECT_NEAR(glm::length(hit->uv - ls->uv), 0.0f, 2e-4f);
        }
    }
    // Without the rotation (the old behaviour) the uv would differ: the test can fail.
    const auto a = rs.intersect(Ray(c + 10.0f * (R * vec3(0.48f, 0.36f, 0.8f)), -(R * vec3(0.48f, 0.36f, 0.8f))));
    const auto w = ps.intersect(Ray(10.0f * (R * vec3(0.48f, 0.36f, 0.8f)), -(R * vec3(0.48f, 0.36f, 0.8f))));
    EXPECT_GT(glm::length(a->uv - w->uv), 0.05f);
}

}  // namespace
}  // namespace iris
