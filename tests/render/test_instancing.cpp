// Mitsuba's `shapegroup` and `instance` shapes (render/loader/instance_loader.cpp, render/scene.cpp,
// render/instance_transform.cpp): a scene of instances renders as the same scene with the group's
// shapes written out in place with the composed transforms (spectral and RGB); a group alone renders
// nothing; the interaction through a non-uniformly scaled instance has normals perpendicular to the
// transformed surface and the group's uv; wrong inputs are refused with their file:line.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/mesh.h"
#include "core/rng.h"
#include "core/sphere_intersection.h"
#include "render/film.h"
#include "render/instance_transform.h"
#include "render/loader/scene_loader.h"
#include "render/renderer.h"
#include "render/scene.h"
#include "tests/support/error_of.h"
#include "tests/support/image_mean.h"
#include "tests/support/render_test_scenes.h"

namespace iris {
namespace {

// ---------------------------------------------------------------- instanced = written in place

/// One shape of a group: its element up to the transform, its own to_world operations, the rest.
struct Member {
    std::string open, ops, rest;
    std::string xml(const std::string& extraOps) const {
        return open + "<transform name=\"to_world\">" + ops + extraOps + "</transform>" + rest + "\n";
    }
};

struct Group {
    std::string id;
    std::vector<Member> members;
    std::vector<std::string> placements;  // each instance's to_world operations
};

const char* kSceneHead = R"(<scene version="3.0.0">
  <integrator type="path"><integer name="max_depth" value="4"/></integrator>
  <sensor type="perspective"><float name="fov" value="50"/>
    <transform name="to_world"><lookat origin="0.3, 1.5, -6" target="0, 0, 0" up="0, 1, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="48"/><integer name="height" value="36"/><rfilter type="box"/></film>
  </sensor>
  <emitter type="constant"><rgb name="radiance" value="0.3, 0.35, 0.4"/></emitter>
  <shape type="rectangle"><transform name="to_world"><rotate x="1" angle="-90"/><scale value="8"/><translate y="-1.2"/></transform>
    <bsdf type="diffuse"><rgb name="reflectance" value="0.6, 0.5, 0.4"/></bsdf></shape>
  <shape type="sphere"><point name="center" x="2" y="4" z="-3"/><float name="radius" value="0.8"/>
    <emitter type="area"><rgb name="radiance" value="6, 5, 4"/></emitter></shape>
)";

/// Three groups: a cube and a sphere placed by translations and uniform scales; a cube and a
/// cylinder placed by rotations too; a textured cube and a rectangle placed by a non-uniform scale
/// and rotations, with a rotated checkered sphere (its uv and tangents turn with its to_world, written
/// out or instanced, as Mitsuba 3's). An analytic shape written in place keeps to rotations,
/// translations and uniform scales.
std::vector<Group> testGroups() {
    const std::string checker = R"(<bsdf type="diffuse"><texture name="reflectance" type="checkerboard">
        <rgb name="color0" value="0.8, 0.2, 0.1"/><rgb name="color1" value="0.1, 0.3, 0.9"/>
        <transform name="to_uv"><scale x="4" y="3"/></transform></texture></bsdf></shape>)";
    const Member cube{"<shape type=\"cube\">", "<scale value=\"0.4\"/><rotate y=\"1\" angle=\"20\"/>",
                      "<bsdf type=\"plastic\"><rgb name=\"diffuse_reflectance\" value=\"0.2, 0.6, 0.3\"/></bsdf></shape>"};
    Group ball{"ball",
               {cube,
                {"<shape type=\"sphere\"><float name=\"radius\" value=\"0.35\"/>", "<translate x=\"0.2\" y=\"0.75\"/>",
                 "<bsdf type=\"roughconductor\"><string name=\"material\" value=\"Au\"/><float name=\"alpha\" value=\"0.2\"/></bsdf></shape>"}},
               {"<translate x=\"-1.4\" y=\"0.3\"/>", "<scale value=\"0.7\"/><translate x=\"1.3\" y=\"0.1\" z=\"0.4\"/>"}};
    Group tube{"tube",
               {cube,
                {"<shape type=\"cylinder\"><float name=\"radius\" value=\"0.15\"/>",
                 "<rotate x=\"1\" angle=\"-90\"/><translate x=\"-0.6\" y=\"-0.4\"/>", "<bsdf type=\"diffuse\"/></shape>"},
                {"<shape type=\"sphere\"><float name=\"radius\" value=\"0.3\"/>",
                 "<rotate x=\"1\" angle=\"50\"/><rotate z=\"1\" angle=\"70\"/><translate x=\"0.5\" y=\"0.7\"/>", checker}},
               {"<rotate y=\"1\" angle=\"30\"/><translate x=\"-0.3\" y=\"0.6\" z=\"1.5\"/>",
                "<scale value=\"0.6\"/><rotate x=\"1\" angle=\"25\"/><rotate z=\"1\" angle=\"-40\"/><translate x=\"2.2\" y=\"-0.5\" z=\"-0.5\"/>"}};
    Group slab{"slab",
               {{"<shape type=\"cube\">", "<scale x=\"0.5\" y=\"0.3\" z=\"0.4\"/>", checker},
                {"<shape type=\"rectangle\">", "<scale value=\"0.4\"/><rotate y=\"1\" angle=\"60\"/><translate x=\"1.1\" z=\"-0.3\"/>", "<bsdf type=\"twosided\"><bsdf type=\"diffuse\"/></bsdf></shape>"}},
               {"<scale x=\"1.8\" y=\"0.6\" z=\"0.9\"/><rotate z=\"1\" angle=\"15\"/><rotate y=\"1\" angle=\"-35\"/><translate y=\"-0.8\" z=\"1.2\"/>"}};
    return {ball, tube, slab};
}

std::string instancedScene(const std::vector<Group>& groups) {
    std::string xml = kSceneHead;
    for (const Group& g : groups) {
        xml += "<shape type=\"shapegroup\" id=\"" + g.id + "\">\n";
        for (const Member& m : g.members) xml += m.xml("");
        xml += "</shape>\n";
        for (const std::string& place : g.placements)
            xml += "<shape type=\"instance\"><ref id=\"" + g.id + "\"/><transform name=\"to_world\">" + place + "</transform></shape>\n";
    }
    return xml + "</scene>\n";
}

/// The same scene with every instance's shapes in place: the shape's own operations, then the
/// instance's (a <transform> applies its operations in order: to_world = instance · shape).
std::string inPlaceScene(const std::vector<Group>& groups) {
    std::string xml = kSceneHead;
    for (const Group& g : groups)
        for (const std::string& place : g.placements)
            for (const Member& m : g.members) xml += m.xml(place);
    return xml + "</scene>\n";
}

/// Fraction of pixels whose channels differ by more than tol (relative to max(value, 0.05)) and
/// the largest such difference.
double differingFraction(const Film& a, const Film& b, double tol) {
    int differ = 0;
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x)
            for (int c = 0; c < 3; ++c) {
                const double u = a.pixel(x, y)[c], v = b.pixel(x, y)[c];
                if (std::abs(u - v) > tol * std::max(0.05, std::abs(v))) {
                    ++differ;
                    break;
                }
            }
    return double(differ) / (a.width() * a.height());
}

TEST(Instancing, RendersAsTheShapesWrittenOutInPlace) {
    // The instanced scene traces the group's shapes in their own space (Embree carries the ray by
    // the inverse of the instance's to_world, in float), the written-out one traces shapes whose
    // vertices, centres and radii were transformed at load: hit points, distances and barycentrics
    // differ by float rounding (~1e-7 relative), so pixel values may differ by about that much
    // (here: 88 % of the pixels are bit-identical, all but 0.5 % agree to 1e-6 and all to 1e-4).
    // A path whose decision sits on a boundary (a silhouette within rounding of the ray, a Russian
    // roulette threshold) could take another turn with other random numbers, so the test allows
    // 1 % of the pixels beyond 1e-4 relative and asks for the image means within 1e-3.
    const std::vector<Group> groups = testGroups();
    const std::string instanced = instancedScene(groups), inPlace = inPlaceScene(groups);
    for (const bool rgb : {true, false}) {
        const Film a = test::renderXml(instanced, 48, 36, 16, 11, rgb);
        const Film b = test::renderXml(inPlace, 48, 36, 16, 11, rgb);
        const double frac = differingFraction(a, b, 1e-4);
        EXPECT_LT(frac, 0.01) << (rgb ? "rgb" : "spectral");
        for (int c = 0; c < 3; ++c) {
            const double ma = test::imageMean(a, c).mean, mb = test::imageMean(b, c).mean;
            EXPECT_GT(mb, 0.01);
            EXPECT_NEAR(ma, mb, 1e-3 * mb) << (rgb ? "rgb" : "spectral") << " channel " << c;
        }
        // The test can fail: an instance placed slightly elsewhere changes many pixels.
        std::vector<Group> moved = groups;
        moved[2].placements[0] += "<translate x=\"0.05\"/>";
        const Film c = test::renderXml(instancedScene(moved), 48, 36, 16, 11, rgb);
        EXPECT_GT(differingFraction(c, b, 1e-4), 0.05);
    }
}

TEST(Instancing, AShapeGroupAloneRendersNothing) {
    const std::string head = R"(<scene version="3.0.0"><integrator type="path"/>
  <sensor type="perspective"><transform name="to_world"><lookat origin="0, 0, -4" target="0, 0, 0" up="0, 1, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/></film></sensor>
  <emitter type="constant"><rgb name="radiance" value="0.5, 0.6, 0.7"/></emitter>
)";
    const std::string group = R"(<shape type="shapegroup" id="g"><shape type="sphere"/><shape type="cube"/></shape>
)";
    const SceneDescription d = loadSceneFromString(head + group + "</scene>", ".");
    EXPECT_TRUE(d.shapes.empty());
    EXPECT_TRUE(d.instances.empty());
    const Scene s(loadSceneFromString(head + group + "</scene>", "."));
    EXPECT_FALSE(s.intersect(Ray(vec3(0, 0, -4), vec3(0, 0, 1))));
    EXPECT_EQ(s.triangleCount(), 0u);
    const Film with = test::renderXml(head + group + "</scene>", 8, 8, 4, 1, true);
    const Film without = test::renderXml(head + "</scene>", 8, 8, 4, 1, true);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) EXPECT_EQ(with.pixel(x, y), without.pixel(x, y));
    // One instance makes it visible.
    const Scene one(loadSceneFromString(head + group + "<shape type=\"instance\"><ref id=\"g\"/></shape></scene>", "."));
    EXPECT_TRUE(one.intersect(Ray(vec3(0, 0, -4), vec3(0, 0, 1))));
    // So does a group nested (without an id) in its instance, as Mitsuba 3 allows.
    const Scene nested(loadSceneFromString(head + "<shape type=\"instance\"><shape type=\"shapegroup\"><shape type=\"sphere\"/></shape>"
                                                  "<transform name=\"to_world\"><translate y=\"3\"/></transform></shape></scene>", "."));
    EXPECT_FALSE(nested.intersect(Ray(vec3(0, 0, -4), vec3(0, 0, 1))));
    EXPECT_TRUE(nested.intersect(Ray(vec3(0, 3, -4), vec3(0, 0, 1))));
}

TEST(Instancing, AMitsuba06SceneLoadsItsInstances) {
    // Mitsuba 0.6 writes the same elements with camelCase names (toWorld).
    const SceneDescription d = loadSceneFromString(R"(<scene version="0.6.0">
  <shape type="shapegroup" id="g"><shape type="sphere"><float name="radius" value="0.5"/></shape>
    <shape type="cube"><boolean name="faceNormals" value="true"/></shape></shape>
  <shape type="instance"><ref id="g"/><transform name="toWorld"><translate x="3"/></transform></shape>
  <shape type="instance"><ref id="g"/></shape>
</scene>)", ".");
    ASSERT_EQ(d.instances.size(), 2u);
    EXPECT_EQ(d.instances[0].group, d.instances[1].group);  // one group, shared
    ASSERT_EQ(d.instances[0].group->shapes.size(), 2u);
    EXPECT_EQ(d.instances[0].toWorld[3], vec4(3, 0, 0, 1));
    EXPECT_EQ(d.instances[1].toWorld, mat4(1.0f));
    const Scene s(loadSceneFromString(R"(<scene version="0.6.0">
  <shape type="shapegroup" id="g"><shape type="sphere"><float name="radius" value="0.5"/></shape></shape>
  <shape type="instance"><ref id="g"/><transform name="toWorld"><translate x="3"/></transform></shape>
</scene>)", "."));
    const auto hit = s.intersect(Ray(vec3(3, 0, -5), vec3(0, 0, 1)));
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->t, 4.5f, 1e-5f);
    EXPECT_LT(glm::length(hit->ng - vec3(0, 0, -1)), 1e-5f);
    EXPECT_EQ(s.bounds().center, vec3(3, 0, 0));
}

TEST(Instancing, EmptyGroupsAndInstancesOfThemTraceNothing) {
    // An empty group, and a group whose only mesh has no triangles, placed twice: no geometry, no
    // bounds, no hit (Embree instances of empty scenes).
    auto empty = std::make_shared<ShapeGroupDescription>();
    auto hollow = std::make_shared<ShapeGroupDescription>();
    ShapeDescription none;
    none.mesh = std::make_shared<TriangleMesh>();
    none.name = "empty mesh";
    hollow->shapes.push_back(none);
    SceneDescription d;
    for (const auto& g : {empty, hollow})
        for (int k = 0; k < 2; ++k) d.instances.push_back(InstanceDescription{g, glm::translate(mat4(1.0f), vec3(float(k))), "i"});
    const Scene s(std::move(d));
    EXPECT_FALSE(s.intersect(Ray(vec3(0, 0, -4), vec3(0, 0, 1))));
    EXPECT_FALSE(s.occluded(Ray(vec3(0, 0, -4), vec3(0, 0, 1))));
    EXPECT_EQ(s.triangleCount(), 0u);
}

TEST(Instancing, AnInstancedMediumBoundaryIsFoundByItsShape) {
    // volpath asks Scene::shape(si.shapeIndex) for the media of the surface it hits: a group's
    // shape is found through any of its instances.
    const Scene s(loadSceneFromString(R"(<scene version="3.0.0"><integrator type="volpath"/>
  <shape type="shapegroup" id="g"><shape type="sphere"><bsdf type="null"/>
    <medium type="homogeneous" name="interior"><rgb name="albedo" value="0.5"/><float name="scale" value="2"/></medium></shape></shape>
  <shape type="cube"/>
  <shape type="instance"><ref id="g"/><transform name="to_world"><translate x="5"/></transform></shape>
  <shape type="instance"><ref id="g"/><transform name="to_world"><translate x="-5"/></transform></shape>
</scene>)", "."));
    for (const float x : {5.0f, -5.0f, 0.0f}) {
        const auto hit = s.intersect(Ray(vec3(x, 0, -5), vec3(0, 0, 1)));
        ASSERT_TRUE(hit);
        EXPECT_EQ(bool(s.shape(hit->shapeIndex).interior), x != 0.0f) << x;
    }
}

// ---------------------------------------------------------------- the transformed interaction

/// Non-uniform scale, rotation and translation.
mat4 skewedPlacement() {
    return glm::translate(mat4(1.0f), vec3(0.3f, -0.2f, 0.5f)) * glm::rotate(mat4(1.0f), 0.6f, glm::normalize(vec3(1, 2, 0.5f))) *
           glm::scale(mat4(1.0f), vec3(2.5f, 0.4f, 1.3f));
}

SceneDescription oneInstance(ShapeDescription shape, const mat4& toWorld) {
    auto group = std::make_shared<ShapeGroupDescription>();
    group->name = "g";
    group->shapes.push_back(std::move(shape));
    SceneDescription d;
    d.instances.push_back(InstanceDescription{group, toWorld, "instance"});
    return d;
}

void expectPerpendicular(const vec3& n, const vec3& t, const char* what) {
    EXPECT_LT(std::abs(glm::dot(n, glm::normalize(t))), 2e-6f) << what;
}

TEST(Instancing, AnEllipsoidThroughANonUniformScaleHasTheRightNormalsAndUV) {
    ShapeDescription sphere;
    sphere.type = ShapeDescription::Type::Sphere;
    sphere.radius = 1.0f;
    sphere.name = "sphere";
    const mat4 m = skewedPlacement();
    const Scene s(oneInstance(sphere, m));
    const vec3 c = transformPoint(m, vec3(0.0f));
    Pcg32 rng(7, 1);
    int hits = 0;
    for (int i = 0; i < 200; ++i) {
        const vec3 target = c + vec3(rng.uniform() - 0.5f, rng.uniform() - 0.5f, rng.uniform() - 0.5f);
        const vec3 o = c + 6.0f * glm::normalize(vec3(rng.uniform() - 0.5f, rng.uniform() - 0.5f, rng.uniform() - 0.5f));
        const auto si = s.intersect(Ray(o, target - o));
        if (!si) continue;
        ++hits;
        // On the ellipsoid: the point in the group's space is on the unit sphere.
        const vec3 local = transformPoint(glm::inverse(m), si->p);
        EXPECT_NEAR(glm::length(local), 1.0f, 1e-5f);
        // The normal is the gradient of |M⁻¹ p|², M⁻ᵀ M⁻¹ (p − c), i.e. the inverse transpose of the
        // sphere's normal; perpendicular to both tangents; outwards; the uv of the sphere's point.
        const vec3 grad = glm::normalize(glm::transpose(glm::inverse(mat3(m))) * local);
        EXPECT_GT(glm::dot(si->ng, grad), 1.0f - 1e-5f);
        EXPECT_EQ(si->ns, si->ng);
        expectPerpendicular(si->ng, si->dpdu, "dpdu");
        expectPerpendicular(si->ng, si->dpdv, "dpdv");
        // Mitsuba's (u, v) = (φ/2π, θ/π) turns against the outward normal (∂p/∂u × ∂p/∂v points in);
        // a placement of positive determinant keeps that orientation.
        EXPECT_LT(glm::dot(glm::cross(si->dpdu, si->dpdv), si->ng), 0.0f);
        EXPECT_LT(glm::length(si->uv - sphereUV(glm::normalize(local))), 1e-5f);
        EXPECT_NEAR(si->t * glm::length(target - o), glm::length(si->p - o), 1e-4f);
        EXPECT_EQ(s.shape(si->shapeIndex).type, ShapeDescription::Type::Sphere);
    }
    EXPECT_GT(hits, 100);
}

TEST(Instancing, AMeshThroughANonUniformScaleMatchesTheTransformedMesh) {
    // A rectangle with vertex normals tilted differently at each corner, instanced, against the same
    // rectangle transformed at load (TriangleMesh::transform): the same point, geometric normal,
    // uv and tangents; the shading normal is the instance transform of the interpolated one.
    ShapeDescription rect;
    rect.mesh = std::make_shared<TriangleMesh>(makeRectangle());
    for (size_t i = 0; i < rect.mesh->normals.size(); ++i)
        rect.mesh->normals[i] = glm::normalize(vec3(0.2f * float(i) - 0.3f, 0.1f * float(i), 1.0f));
    rect.name = "rectangle";
    const mat4 m = skewedPlacement();
    const Scene instanced(oneInstance(rect, m));
    SceneDescription flat;
    ShapeDescription moved = rect;
    moved.mesh = std::make_shared<TriangleMesh>(*rect.mesh);
    moved.mesh->transform(m);
    flat.shapes.push_back(moved);
    const Scene written(std::move(flat));
    SceneDescription untransformed;
    untransformed.shapes.push_back(rect);
    const Scene inGroupSpace(std::move(untransformed));
    const mat3 normalMatrix = glm::transpose(glm::inverse(mat3(m)));
    int hits = 0;
    for (float u = -0.9f; u < 0.95f; u += 0.3f)
        for (float v = -0.9f; v < 0.95f; v += 0.3f) {
            const vec3 p = transformPoint(m, vec3(u, v, 0.0f));
            const vec3 n = glm::normalize(normalMatrix * vec3(0, 0, 1));
            const Ray ray(p + 3.0f * n + vec3(0.1f, -0.2f, 0.05f), -3.0f * n - vec3(0.1f, -0.2f, 0.05f));
            const auto a = instanced.intersect(ray), b = written.intersect(ray);
            ASSERT_TRUE(a && b);
            ++hits;
            EXPECT_LT(glm::length(a->p - b->p), 1e-5f);
            EXPECT_LT(glm::length(a->ng - b->ng), 1e-5f);
            EXPECT_LT(glm::length(a->uv - b->uv), 1e-5f);
            EXPECT_LT(glm::length(a->dpdu - b->dpdu), 1e-5f * glm::length(b->dpdu));
            EXPECT_LT(glm::length(a->dpdv - b->dpdv), 1e-5f * glm::length(b->dpdv));
            EXPECT_NEAR(a->t, b->t, 1e-5f);
            expectPerpendicular(a->ng, a->dpdu, "dpdu");
            expectPerpendicular(a->ng, a->dpdv, "dpdv");
            // The shading normal: the one of the rectangle in the group's space, hit by the ray
            // carried there, under the inverse transpose.
            const auto local = inGroupSpace.intersect(InstanceTransform(m).toObjectRay(ray));
            ASSERT_TRUE(local);
            EXPECT_LT(glm::length(a->ns - glm::normalize(normalMatrix * local->ns)), 1e-5f);
            EXPECT_GT(glm::dot(a->ns, a->ng), 0.5f);
        }
    EXPECT_EQ(hits, 49);
}

TEST(Instancing, InstanceTransformCarriesTheInteraction) {
    const InstanceTransform t(skewedPlacement());
    SurfaceInteraction si;
    si.p = vec3(0.5f, -0.25f, 0.0f);
    si.ng = si.ns = vec3(0, 0, 1);
    si.dpdu = vec3(2, 0, 0);
    si.dpdv = vec3(0, 2, 0);
    si.uv = vec2(0.75f, 0.375f);
    si.dpScale = 3.0f;
    t.toWorldInteraction(si);
    EXPECT_LT(glm::length(si.p - transformPoint(t.toWorld, vec3(0.5f, -0.25f, 0.0f))), 1e-6f);
    expectPerpendicular(si.ng, si.dpdu, "dpdu");
    expectPerpendicular(si.ns, si.dpdv, "dpdv");
    EXPECT_NEAR(glm::length(si.ns), 1.0f, 1e-6f);
    EXPECT_EQ(si.uv, vec2(0.75f, 0.375f));
    EXPECT_EQ(si.dpScale, 3.0f);
    const Ray r = t.toObjectRay(Ray(transformPoint(t.toWorld, vec3(1, 2, 3)), transformVector(t.toWorld, vec3(0, 0, 1)), 5.0f));
    EXPECT_LT(glm::length(r.o - vec3(1, 2, 3)), 1e-5f);
    EXPECT_LT(glm::length(r.d - vec3(0, 0, 1)), 1e-5f);
    EXPECT_EQ(r.tMax, 5.0f);
}

// ---------------------------------------------------------------- wrong inputs

std::string loadError(const std::string& body) { return test::sceneError(body); }
const auto has = test::contains;

TEST(Instancing, WrongInputsAreRefusedWithTheirLine) {
    const std::string noRef = loadError("<shape type=\"instance\"/>\n");
    EXPECT_TRUE(has(noRef, "<string>:2: an instance needs a shapegroup")) << noRef;

    const std::string notGroup = loadError("<bsdf type=\"diffuse\" id=\"d\"/>\n<shape type=\"instance\"><ref id=\"d\"/></shape>\n");
    EXPECT_TRUE(has(notGroup, "<string>:3: an instance refers only to a shapegroup")) << notGroup;
    EXPECT_TRUE(has(notGroup, "<bsdf type=\"diffuse\" id=\"d\"> (defined at <string>:2)")) << notGroup;
    const std::string aShape = loadError("<shape type=\"sphere\" id=\"s\"/>\n<shape type=\"instance\"><ref id=\"s\"/></shape>\n");
    EXPECT_TRUE(has(aShape, "<string>:3: an instance refers only to a shapegroup")) << aShape;

    const std::string unknown = loadError("<shape type=\"instance\">\n<ref id=\"nowhere\"/></shape>\n");
    EXPECT_TRUE(has(unknown, "<string>:3: <ref>: unknown id 'nowhere'")) << unknown;

    const std::string two = loadError("<shape type=\"shapegroup\" id=\"a\"><shape type=\"sphere\"/></shape>\n"
                                      "<shape type=\"instance\"><ref id=\"a\"/><ref id=\"a\"/></shape>\n");
    EXPECT_TRUE(has(two, "<string>:3: an instance refers to exactly one shapegroup")) << two;

    const std::string emitter = loadError("<shape type=\"shapegroup\" id=\"g\">\n"
                                          "<shape type=\"sphere\"><emitter type=\"area\"><rgb name=\"radiance\" value=\"1\"/></emitter></shape>\n"
                                          "</shape>\n<shape type=\"instance\"><ref id=\"g\"/></shape>\n");
    EXPECT_TRUE(has(emitter, "<string>:3: shape 'sphere' in shapegroup 'g' has an area emitter: instancing of emitters is not supported"))
        << emitter;
    EXPECT_EQ(std::count(emitter.begin(), emitter.end(), '\n'), 0) << emitter;  // once, not again for the instance

    const std::string nested = loadError("<shape type=\"shapegroup\" id=\"outer\">\n<shape type=\"shapegroup\" id=\"inner\">"
                                         "<shape type=\"sphere\"/></shape>\n</shape>\n");
    EXPECT_TRUE(has(nested, "<string>:3: a shapegroup cannot contain another shapegroup")) << nested;
    EXPECT_TRUE(has(nested, "in shapegroup 'outer' at <string>:2")) << nested;

    const std::string inner = loadError("<shape type=\"shapegroup\" id=\"a\"><shape type=\"sphere\"/></shape>\n"
                                        "<shape type=\"shapegroup\" id=\"b\">\n<shape type=\"instance\"><ref id=\"a\"/></shape></shape>\n");
    EXPECT_TRUE(has(inner, "<string>:4: a shapegroup cannot contain an instance")) << inner;

    const std::string light = loadError("<shape type=\"shapegroup\" id=\"g\">\n<emitter type=\"point\"/></shape>\n");
    EXPECT_TRUE(has(light, "<string>:3: a shapegroup holds only shapes, not a <emitter>")) << light;

    const std::string param = loadError("<shape type=\"shapegroup\" id=\"g\"><shape type=\"sphere\"/></shape>\n"
                                        "<shape type=\"instance\"><ref id=\"g\"/>\n<float name=\"radius\" value=\"2\"/></shape>\n");
    EXPECT_TRUE(has(param, "<string>:4: unknown parameter 'radius'")) << param;

    const std::string flat = loadError("<shape type=\"shapegroup\" id=\"g\"><shape type=\"sphere\"/></shape>\n"
                                       "<shape type=\"instance\"><ref id=\"g\"/>\n<transform name=\"to_world\"><scale z=\"0\"/></transform></shape>\n");
    EXPECT_TRUE(has(flat, "<string>:4: the instance's to_world is not invertible")) << flat;

    // A group's shape keeps its own rules: a sphere under a non-uniform to_world is refused.
    const std::string skew = loadError("<shape type=\"shapegroup\" id=\"g\">\n<shape type=\"sphere\"><transform name=\"to_world\">"
                                       "<scale x=\"2\"/></transform></shape></shape>\n");
    EXPECT_TRUE(has(skew, "<string>:3:")) << skew;
}

}  // namespace
}  // namespace iris
