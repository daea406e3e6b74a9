// The analytic open cylinder (Mitsuba "cylinder"; render/shapes/cylinder.cpp,
// core/cylinder_intersection.h): roots against the wall and its ends (no caps), from far away
// and at grazing angles; rays leaving a hit point do not find their own wall again; uv and
// ∂p/∂u, ∂p/∂v as Mitsuba 3's parametrisation (checked against finite differences); the normal and
// flip_normals; an emitting cylinder lights a floor as a finely tessellated mesh cylinder does
// (area sampling, pdf); wrong cylinders are refused with their line.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "core/error.h"
#include "core/frame.h"
#include "core/ray.h"
#include "core/rng.h"
#include "core/cylinder_intersection.h"
#include "render/film.h"
#include "render/loader/scene_loader.h"
#include "render/renderer.h"
#include "render/scene.h"
#include "spectral/spectrum_factory.h"
#include "tests/support/error_of.h"
#include "tests/support/image_mean.h"
#include "tests/support/render_test_scenes.h"

namespace iris {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

CylinderGeometry zCylinder(float length) {
    CylinderGeometry c;
    c.length = length;
    return c;
}

TEST(CylinderIntersection, WallRootsEndsAndGrazingRays) {
    const CylinderGeometry c = zCylinder(2.0f);
    const dvec3 x(1, 0, 0), z(0, 0, 1);
    // Head-on from far away: the near wall at distance 1e7 − 1.
    EXPECT_NEAR(intersectCylinder(dvec3(-1e7, 0, 1), x, c, 1.0, 0.0, kInf), 1e7 - 1.0, 1e-8 * 1e7);
    // From inside the tube: the wall ahead.
    EXPECT_NEAR(intersectCylinder(dvec3(0.25, 0, 1), x, c, 1.0, 0.0, kInf), 0.75, 1e-15);
    // No caps: a ray along the axis, and a ray that enters through the open end and leaves through
    // it again without touching the wall, miss; one that leaves through the wall hits it from inside.
    EXPECT_EQ(intersectCylinder(dvec3(0, 0, -5), z, c, 1.0, 0.0, kInf), kInf);
    EXPECT_EQ(intersectCylinder(dvec3(0.5, 0, -5), z, c, 1.0, 0.0, kInf), kInf);
    const dvec3 slant = glm::normalize(dvec3(1, 0, 2));
    const double t = intersectCylinder(dvec3(0, 0, -0.5), slant, c, 1.0, 0.0, kInf);
    EXPECT_NEAR(t, std::sqrt(5.0), 1e-12);  // x = 1 at z = 1.5: t = |(1, 0, 2)|
    // Above or below the ends: the wall hit is outside [0, length] and does not count.
    EXPECT_EQ(intersectCylinder(dvec3(-5, 0, 2.5), x, c, 1.0, 0.0, kInf), kInf);
    EXPECT_EQ(intersectCylinder(dvec3(-5, 0, -0.01), x, c, 1.0, 0.0, kInf), kInf);
    // Grazing: an impact parameter just inside and just outside the radius.
    const double in = intersectCylinder(dvec3(-5, 1.0 - 1e-9, 1), x, c, 1.0, 0.0, kInf);
    EXPECT_NEAR(in, 5.0 - std::sqrt(1.0 - (1.0 - 1e-9) * (1.0 - 1e-9)), 1e-9);
    EXPECT_EQ(intersectCylinder(dvec3(-5, 1.0 + 1e-9, 1), x, c, 1.0, 0.0, kInf), kInf);
    // tMin and tMax bound the roots; the far wall is found beyond the near one; unnormalised d.
    EXPECT_EQ(intersectCylinder(dvec3(-5, 0, 1), x, c, 1.0, 0.0, 3.9), kInf);
    EXPECT_NEAR(intersectCylinder(dvec3(-5, 0, 1), x, c, 1.0, 4.5, kInf), 6.0, 1e-14);
    EXPECT_NEAR(intersectCylinder(dvec3(-5, 0, 1), 4.0 * x, c, 1.0, 0.0, kInf), 1.0, 1e-15);
}

TEST(CylinderIntersection, RandomRaysHitTheWallWithinItsLength) {
    // Any axis and position: the hit lies on the wall (distance r from the axis) within [0, L],
    // and a brute-force march along the ray finds no wall crossing before it.
    Pcg32 rng(17, 1);
    for (int i = 0; i < 2000; ++i) {
        CylinderGeometry c;
        const vec3 axis = glm::normalize(vec3(rng.uniform() - 0.5f, rng.uniform() - 0.5f, rng.uniform() - 0.5f));
        const Frame f = Frame::fromNormal(axis);
        c.axis = f.n;
        c.s = f.s;
        c.t = f.t;
        c.p0 = vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 100.0f - 50.0f;
        c.length = 0.5f + 3.0f * rng.uniform();
        const double r = 0.2 + rng.uniform();
        const dvec3 target = dvec3(c.p0) + double(c.length * rng.uniform()) * dvec3(c.axis) + 1.5 * r * dvec3(c.s);
        const dvec3 o = target + dvec3(rng.uniform() - 0.5f, rng.uniform() - 0.5f, rng.uniform() - 0.5f) * 20.0;
        const dvec3 d = glm::normalize(target - o + dvec3(rng.uniform() - 0.5f, rng.uniform() - 0.5f, 0.0) * r);
        const double t = intersectCylinder(o, d, c, r, 0.0, kInf);
        auto dist = [&](double s) {
            const dvec3 q = o + s * d - dvec3(c.p0);
            const double h = glm::dot(q, dvec3(c.axis));
            return std::make_pair(glm::length(q - h * dvec3(c.axis)) - r, h);
        };
        if (std::isfinite(t)) {
            const auto [e, h] = dist(t);
            EXPECT_NEAR(e, 0.0, 1e-9 * (1 + glm::length(o)));
            EXPECT_GE(h, -1e-9);
            EXPECT_LE(h, c.length + 1e-9);
        }
        // No wall crossing within [0, L] before t (steps of r/50).
        const double end = std::isfinite(t) ? t : 60.0;
        for (double s = 0.0; s + r / 50 < end; s += r / 50) {
            const auto [e0, h0] = dist(s);
            const auto [e1, h1] = dist(s + r / 50);
            if (e0 * e1 < 0 && h0 >= 0 && h1 >= 0 && h0 <= c.length && h1 <= c.length && s + r / 50 < end - 1e-6)
                ADD_FAILURE() << "ray " << i << " crosses the wall at " << s << " before the reported t " << t;
        }
    }
}

TEST(CylinderShape, UvDerivativesAndNormalAreMitsubas) {
    // p0 = (1, 0, 0), p1 = (1, 0, 3), radius 2: Frame3f((0, 0, 1)) has s = (1, 0, 0), t = (0, 1, 0),
    // so the point at angle φ and height h has u = φ/2π, v = h/3, ∂p/∂u = 2π r (−sin φ, cos φ, 0),
    // ∂p/∂v = (0, 0, 3) and the outward normal (cos φ, sin φ, 0).
    const std::string xml = R"(<scene version="3.0.0">
  <shape type="cylinder"><point name="p0" x="1" y="0" z="0"/><point name="p1" x="1" y="0" z="3"/>
    <float name="radius" value="2"/></shape>
</scene>)";
    Scene scene(loadSceneFromString(xml, "."));
    const vec3 axisPoint(1, 0, 0);
    const float r = 2.0f;
    auto hitAt = [&](float phi, float h) {
        const vec3 n(std::cos(phi), std::sin(phi), 0.0f);
        const auto hit = scene.intersect(Ray(axisPoint + vec3(0, 0, h) + 10.0f * n, -n));
        EXPECT_TRUE(hit.has_value());
        return *hit;
    };
    const float phi = 2.2f, h = 1.2f;
    const SurfaceInteraction a = hitAt(phi, h);
    EXPECT_NEAR(a.uv.x, phi / (2 * kPi), 1e-5f);
    EXPECT_NEAR(a.uv.y, h / 3.0f, 1e-5f);
    EXPECT_NEAR(glm::length(a.p - vec3(1, 0, h)), r, 1e-5f);
    EXPECT_NEAR(glm::dot(a.ng, vec3(std::cos(phi), std::sin(phi), 0)), 1.0f, 1e-6f);
    EXPECT_EQ(a.dpScale, 1.0f);
    EXPECT_NEAR(a.dpdu.x, -2 * kPi * r * std::sin(phi), 1e-3f);
    EXPECT_NEAR(a.dpdu.y, 2 * kPi * r * std::cos(phi), 1e-3f);
    EXPECT_NEAR(glm::length(a.dpdv - vec3(0, 0, 3)), 0.0f, 1e-5f);
    const float e = 1e-3f;
    const SurfaceInteraction du = hitAt(phi + e, h), dv = hitAt(phi, h + e);
    const vec3 fu = (du.p - a.p) / (du.uv.x - a.uv.x), fv = (dv.p - a.p) / (dv.uv.y - a.uv.y);
    EXPECT_LT(glm::length(fu - a.dpdu), 2e-2f * glm::length(a.dpdu));
    EXPECT_LT(glm::length(fv - a.dpdv), 2e-2f * glm::length(a.dpdv));
    // flip_normals turns the normal inwards; the hit and uv stay.
    const std::string flipped = R"(<scene version="3.0.0">
  <shape type="cylinder"><point name="p0" x="1" y="0" z="0"/><point name="p1" x="1" y="0" z="3"/>
    <float name="radius" value="2"/><boolean name="flip_normals" value="true"/></shape>
</scene>)";
    Scene scene2(loadSceneFromString(flipped, "."));
    const auto b = scene2.intersect(Ray(vec3(1, 0, h) + 10.0f * vec3(std::cos(phi), std::sin(phi), 0), -vec3(std::cos(phi), std::sin(phi), 0)));
    ASSERT_TRUE(b.has_value());
    EXPECT_NEAR(glm::dot(b->ng, vec3(std::cos(phi), std::sin(phi), 0)), -1.0f, 1e-6f);
    EXPECT_NEAR(b->uv.x, a.uv.x, 1e-6f);
}

TEST(CylinderShape, RaysLeavingAHitPointDoNotFindTheirOwnWall) {
    // Small and large radii, 200 radii from the origin (the spawn offset, 2e-5 (1 + max|p|), stays
    // small against the radius; core/ray.h): a ray leaving the outside of the wall outwards misses
    // the cylinder; one leaving inwards hits the far wall, on the wall.
    for (const float r : {1e-2f, 1.0f, 1e3f}) {
        const float cx = 200.0f * r;
        const std::string xml = "<scene version=\"3.0.0\"><shape type=\"cylinder\"><point name=\"p0\" x=\"" +
                                std::to_string(cx) + "\" y=\"0\" z=\"0\"/><point name=\"p1\" x=\"" + std::to_string(cx) +
                                "\" y=\"0\" z=\"" + std::to_string(4 * r) + "\"/><float name=\"radius\" value=\"" +
                                std::to_string(r) + "\"/></shape></scene>";
        Scene scene(loadSceneFromString(xml, "."));
        Pcg32 rng(3, 1);
        int selfHits = 0;
        for (int i = 0; i < 500; ++i) {
            const float phi = 2 * kPi * rng.uniform(), h = r * (1 + 2 * rng.uniform());
            const vec3 n(std::cos(phi), std::sin(phi), 0.0f);
            const auto hit = scene.intersect(Ray(vec3(cx, 0, h) + 3 * r * n, -n));
            ASSERT_TRUE(hit.has_value());
            const vec3 out = glm::normalize(n + vec3(0.3f * (rng.uniform() - 0.5f), 0.3f * (rng.uniform() - 0.5f), 0));
            if (scene.intersect(hit->spawnRay(out))) ++selfHits;
            const vec3 in = glm::normalize(-n + vec3(0, 0.2f * (rng.uniform() - 0.5f), 0));
            const auto far = scene.intersect(hit->spawnRay(in));
            if (!far || far->t < 0.5f * r) {
                ++selfHits;
                continue;
            }
            EXPECT_NEAR(glm::length(vec2(far->p.x - cx, far->p.y)), r, 1e-4f * r + 1e-3f);
        }
        EXPECT_EQ(selfHits, 0) << "radius " << r;
    }
}

/// A tessellated open cylinder (outward normals), the same geometry as `c`.
TriangleMesh meshCylinder(const CylinderGeometry& c, float r, int segments) {
    TriangleMesh m;
    for (int i = 0; i < segments; ++i) {
        const float phi = 2 * kPi * float(i) / float(segments);
        const vec3 radial = std::cos(phi) * c.s + std::sin(phi) * c.t;
        m.positions.push_back(c.p0 + r * radial);
        m.positions.push_back(c.p0 + c.length * c.axis + r * radial);
    }
    for (int i = 0; i < segments; ++i) {
        const uint32_t b0 = 2 * i, t0 = 2 * i + 1, b1 = 2 * ((i + 1) % segments), t1 = b1 + 1;
        m.indices.insert(m.indices.end(), {b0, b1, t1, b0, t1, t0});
    }
    return m;
}

double floorRadiance(ShapeDescription light, const char* integrator, bool rgb, double* stderrOut) {
    SceneDescription d;
    d.sourceFile = "<cylinder light>";
    ShapeDescription floor;
    floor.mesh = std::make_shared<TriangleMesh>(makeRectangle());
    floor.mesh->transform(glm::scale(mat4(1.0f), vec3(100.0f)));
    floor.material = testing::makeDiffuse(0.5f);
    floor.name = "floor";
    d.shapes.push_back(floor);
    d.shapes.push_back(std::move(light));
    mat4 cam(1.0f);  // looking straight down at the origin from z = 0.5 (x left, y up, z forward)
    cam[0] = vec4(-1, 0, 0, 0);
    cam[1] = vec4(0, 1, 0, 0);
    cam[2] = vec4(0, 0, -1, 0);
    cam[3] = vec4(0, 0, 0.5f, 1);
    testing::setCamera(d.camera, cam, 0.01f, 4, 4);
    d.integrator = testing::makeIntegrator(integrator, 2);
    const Scene scene(std::move(d));
    RenderOptions opt;
    opt.rgbMode = rgb;
    opt.spp = 4096;
    opt.seed = 5;
    Film film(4, 4);
    Renderer(scene, opt).render(film);
    const test::ImageMean m = test::imageMean(film, 1);
    *stderrOut = m.stderr_;
    return m.mean;
}

TEST(CylinderLight, LightsAFloorAsATessellatedCylinderDoes) {
    // A tilted emitting cylinder above the floor point: its irradiance through area sampling, next-
    // event estimation and MIS must equal that of a 2048-segment mesh cylinder (mesh area lights
    // are checked against analytic irradiance in test_lights.cpp; the tessellation changes the
    // area by 4e-7).
    CylinderGeometry c;
    const Frame f = Frame::fromNormal(glm::normalize(vec3(1, 0.5f, 0.3f)));
    c.axis = f.n;
    c.s = f.s;
    c.t = f.t;
    c.p0 = vec3(-1.2f, -0.4f, 1.5f);
    c.length = 2.0f;
    const float r = 0.3f, L = 5.0f;
    ShapeDescription analytic;
    analytic.type = ShapeDescription::Type::Cylinder;
    analytic.cylinder = c;
    analytic.radius = r;
    analytic.emission = std::make_shared<ConstantSpectrum>(L, SpectrumKind::Illuminant);
    analytic.material = testing::makeDiffuse(0.0f);
    analytic.name = "cylinder";
    ShapeDescription mesh = analytic;
    mesh.type = ShapeDescription::Type::Mesh;
    mesh.mesh = std::make_shared<TriangleMesh>(meshCylinder(c, r, 2048));
    for (const char* integrator : {"direct", "path"}) {
        for (const bool rgb : {true, false}) {
            double seA, seM;
            const double a = floorRadiance(analytic, integrator, rgb, &seA);
            const double m = floorRadiance(mesh, integrator, rgb, &seM);
            EXPECT_GT(a, 0.01);
            EXPECT_NEAR(a, m, 5 * std::sqrt(seA * seA + seM * seM) + 1e-4 * m) << integrator << (rgb ? " rgb" : " spectral");
            // The test can fail: a cylinder 10 % thicker is outside the tolerance.
            ShapeDescription thicker = analytic;
            thicker.radius = 1.1f * r;
            double seT;
            const double t = floorRadiance(thicker, integrator, rgb, &seT);
            EXPECT_GT(std::abs(t - m), 5 * std::sqrt(seT * seT + seM * seM)) << integrator;
        }
    }
}

TEST(CylinderShape, WrongCylindersAreRefusedWithTheirLine) {
    const auto err = [](const std::string& body) { return test::sceneError(body); };
    const auto has = test::contains;
    const std::string r0 = err("<shape type=\"cylinder\">\n<float name=\"radius\" value=\"0\"/></shape>\n");
    EXPECT_TRUE(has(r0, "<string>:3: cylinder radius must be positive")) << r0;
    const std::string same = err("<shape type=\"cylinder\">\n<point name=\"p0\" x=\"0\" y=\"0\" z=\"1\"/>\n"
                                 "<point name=\"p1\" x=\"0\" y=\"0\" z=\"1\"/></shape>\n");
    EXPECT_TRUE(has(same, "<string>:4: cylinder: p0 and p1 must be distinct")) << same;
    const std::string scaled = err("<shape type=\"cylinder\">\n<transform name=\"to_world\"><scale x=\"2\" y=\"1\" z=\"1\"/></transform></shape>\n");
    EXPECT_TRUE(has(scaled, "<string>:3: cylinder: to_world must scale the two directions across the axis equally")) << scaled;
    const std::string sheared = err("<shape type=\"cylinder\">\n<transform name=\"to_world\"><matrix value=\"1 0 0.5 0  0 1 0 0  0 0 1 0  0 0 0 1\"/></transform></shape>\n");
    EXPECT_TRUE(has(sheared, "<string>:3: cylinder: to_world must not shear")) << sheared;
    const std::string medium = err("<medium type=\"homogeneous\" id=\"m\"/>\n<shape type=\"cylinder\">\n<ref name=\"interior\" id=\"m\"/></shape>\n");
    EXPECT_TRUE(has(medium, "a cylinder has no end caps")) << medium;
    const std::string unknown = err("<shape type=\"cylinder\">\n<float name=\"raduis\" value=\"1\"/></shape>\n");
    EXPECT_TRUE(has(unknown, "raduis")) << unknown;
    // Accepted: defaults, a rotated and uniformly scaled cylinder, an emitter on it; a scale along
    // the axis (Mitsuba 3's test_various_shapes scales a cylinder by (1.5, 1.5, 2)).
    EXPECT_EQ(err("<shape type=\"cylinder\"/>\n"), "");
    EXPECT_EQ(err("<shape type=\"cylinder\"><transform name=\"to_world\"><rotate x=\"1\" angle=\"30\"/><scale value=\"3\"/>"
                  "</transform><emitter type=\"area\"><rgb name=\"radiance\" value=\"1\"/></emitter></shape>\n"),
              "");
    EXPECT_EQ(err("<shape type=\"cylinder\"><transform name=\"to_world\"><scale x=\"1.5\" y=\"1.5\" z=\"2\"/></transform></shape>\n"), "");
}

TEST(CylinderShape, AScaleAlongTheAxisSetsTheLengthAndTheOtherTheRadius) {
    // scale (1.5, 1.5, 2), then rotated 90° about y (the axis becomes +x): radius 1.5, the wall
    // from x = 0 to x = 2.
    const std::string xml = R"(<scene version="3.0.0"><shape type="cylinder"><transform name="to_world">
        <scale x="1.5" y="1.5" z="2"/><rotate y="1" angle="90"/></transform></shape></scene>)";
    Scene scene(loadSceneFromString(xml, "."));
    const auto hitAt = [&](float x) { return scene.intersect(Ray(vec3(x, 5.0f, 0.0f), vec3(0.0f, -1.0f, 0.0f))); };
    const auto mid = hitAt(1.0f);
    ASSERT_TRUE(mid.has_value());
    EXPECT_NEAR(mid->p.y, 1.5f, 1e-5f);  // the radius
    EXPECT_NEAR(mid->uv.y, 0.5f, 1e-5f);  // v = position / length
    EXPECT_TRUE(hitAt(1.95f).has_value());
    EXPECT_FALSE(hitAt(2.05f).has_value());  // beyond the length 2
    EXPECT_FALSE(hitAt(-0.05f).has_value());
}

}  // namespace
}  // namespace iris
