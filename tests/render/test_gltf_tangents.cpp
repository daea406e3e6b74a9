// Tangents generated for glTF normal textures when the file has no TANGENT (glTF 2.0 §3.7.2.1:
// "client implementations SHOULD calculate tangents using default MikkTSpace algorithms";
// render/loader/gltf_tangents.h): on the flat quad of normal_mapped.gltf (the per-triangle ∂p/∂u
// of before, and the same image), on the mirrored pair of normal_mirrored.gltf (w = −1 on the
// mirrored half, and the normal map tilts the same way on both halves), on a cylinder built here
// as a triangle soup (welded, smooth, ⟂ N, the analytic ∂p/∂u), with a file's TANGENT (kept as it
// is) and with degenerate or missing UVs (finite tangents orthogonal to N).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "core/error.h"
#include "core/source_tree.h"
#include "materials/gltf_normal_map.h"
#include "materials/gltf_texture.h"
#include "materials/perturbed_frame.h"
#include "render/film.h"
#include "render/loader/gltf_loader.h"
#include "render/loader/gltf_tangents.h"
#include "render/loader/scene_file.h"
#include "render/renderer.h"
#include "render/scene.h"

namespace iris {
namespace {

constexpr float kPi = 3.14159265358979f;

std::string asset(const std::string& name) { return sourcePath("tests/data/gltf/" + name); }

SceneDescription load(const std::string& name, int width = 0) {
    std::ifstream in(asset(name));
    std::stringstream ss;
    ss << in.rdbuf();
    GltfOptions o;
    if (width > 0) o.width = width;
    return loadGltfSceneFromMemory(ss.str(), name, sourcePath("tests/data/gltf"), o);
}

/// The tangent attribute (xyz, w) of vertex v (0 and a failure when there is none).
vec4 tangentOf(const TriangleMesh& m, size_t v) {
    const MeshAttribute* a = m.findAttribute(gltf::kTangentAttribute);
    if (!a || a->channels != 4) {
        ADD_FAILURE() << m.name << " has no tangents";
        return vec4(0.0f);
    }
    return vec4(a->value(v, 0), a->value(v, 1), a->value(v, 2), a->value(v, 3));
}

void expectNear(const vec3& got, const vec3& want, float tol, const std::string& what) {
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(got[i], want[i], tol) << what << " component " << i;
}

/// Tangent (xyz, w) `got` is `want` exactly, component by component.
void expectTangent(const vec4& got, const vec4& want, const std::string& what) {
    for (int i = 0; i < 4; ++i) EXPECT_EQ(got[i], want[i]) << what << (i < 3 ? " component " : " w ") << i;
}

/// The world shading normal and tangent frame the material gives a ray straight down onto (x, z).
struct Hit {
    vec3 normal;
    gltf::TangentFrame frame;
};
Hit hitAt(const Scene& scene, float x, float z) {
    const std::optional<SurfaceInteraction> si = scene.intersect(Ray(vec3(x, 3.0f, z), vec3(0, -1, 0)));
    if (!si) throw std::runtime_error("missed");
    const ShadingPoint sp = shadingPointAt(*si);
    const auto* mapped = dynamic_cast<const PerturbedMaterial*>(si->material);
    if (!mapped) throw std::runtime_error("not normal-mapped");
    return {sp.shading.toWorld(glm::normalize(mapped->perturbation(sp))), gltf::tangentFrameAt(sp)};
}

/// The spec's n' = normalize(x T + y B + z N), B = (N × T) · w, with make_assets.py's texel
/// (191, 90, 223) at scale 0.5: x > 0 tilts towards T, y < 0 away from B.
vec3 specNormal(const vec3& T, const vec3& N, float w) {
    const vec3 c = vec3(191, 90, 223) / 255.0f;
    const vec3 local = glm::normalize((c * 2.0f - 1.0f) * vec3(0.5f, 0.5f, 1.0f));
    const vec3 B = glm::cross(N, T) * w;
    return glm::normalize(local.x * T + local.y * B + local.z * N);
}

Film render(const SceneDescription& d) {
    RenderOptions opt;
    opt.spp = 4;
    opt.seed = 7;
    Film f(d.camera.width, d.camera.height);
    Renderer(Scene(d), opt).render(f);
    return f;
}

// (a) The flat, unmirrored quad: generated T = ∂p/∂u = +x, w = 1 at every vertex, and the image
// is the one of the per-triangle rule of before (the same mesh with its tangents removed, which
// materials/gltf_normal_map.cpp still falls back to).
TEST(GltfTangents, FlatQuadIsThePerTriangleDerivative) {
    const SceneDescription generated = load("normal_mapped.gltf", 24);
    const TriangleMesh& quad = *generated.shapes[1].mesh;  // node "computed"
    ASSERT_EQ(quad.positions.size(), 4u) << "nothing to split";
    for (size_t v = 0; v < 4; ++v) expectTangent(tangentOf(quad, v), vec4(1, 0, 0, 1), "vertex " + std::to_string(v));
    SceneDescription perTriangle = load("normal_mapped.gltf", 24);
    auto stripped = std::make_shared<TriangleMesh>(*perTriangle.shapes[1].mesh);
    stripped->attributes.clear();
    perTriangle.shapes[1].mesh = stripped;
    const Film a = render(generated), b = render(perTriangle);
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x)
            for (int c = 0; c < 3; ++c) {
                const float pa = a.pixel(x, y)[c], pb = b.pixel(x, y)[c];
                ASSERT_NEAR(pa, pb, 1e-4f * std::max(1.0f, std::abs(pb))) << x << "," << y << " channel " << c;
            }
}

// (b) The mirrored pair: the seam's two shared vertices are split (6 → 8), the mirrored half has
// T = −x and w = −1, so B = (N × T) · w = −z on both halves, and the texel's tilt along the
// bitangent goes the same way in the world on both. Deliberately failing on the old rule (w = 1
// always, B = +z on the right half): run against the importer with the generation switched off
// (the per-triangle fallback of materials/gltf_normal_map.cpp), this test failed as it should —
// no tangents and 6 vertices, and on the right half n'.z = −0.183 instead of +0.183.
TEST(GltfTangents, MirroredUVsFlipTheBitangent) {
    const SceneDescription d = load("normal_mirrored.gltf");
    const TriangleMesh& m = *d.shapes.at(0).mesh;
    EXPECT_EQ(m.positions.size(), 8u) << "the seam's vertices, used by both orientations, are split";
    for (size_t tri = 0; tri < m.triangleCount(); ++tri) {
        const bool right = m.positions[m.indices[3 * tri]].x + m.positions[m.indices[3 * tri + 1]].x +
                               m.positions[m.indices[3 * tri + 2]].x > 0.0f;
        for (int k = 0; k < 3; ++k) {
            const vec4 t = tangentOf(m, m.indices[3 * tri + size_t(k)]);
            expectTangent(t, right ? vec4(-1, 0, 0, -1) : vec4(1, 0, 0, 1), strCat("triangle ", tri, " corner ", k));
        }
    }
    const Scene scene(load("normal_mirrored.gltf"));
    const vec3 N(0, 1, 0);
    for (const float x : {-1.3f, -0.05f, 0.05f, 1.3f}) {
        const Hit h = hitAt(scene, x, 0.2f);
        expectNear(h.frame.b, vec3(0, 0, -1), 1e-5f, "bitangent −∂p/∂v at x " + std::to_string(x));
        const vec3 T = x < 0 ? vec3(1, 0, 0) : vec3(-1, 0, 0);
        expectNear(h.normal, specNormal(T, N, x < 0 ? 1.0f : -1.0f), 2e-5f, "n' at x " + std::to_string(x));
        EXPECT_GT(h.normal.z, 0.1f) << "the texel's green < 0.5 tilts away from B = −z on both halves, x " << x;
    }
}

/// A cylinder of radius 1 about y as a triangle soup (every triangle its own three vertices, so
/// only welding joins them): u = φ / 2π around, v = (1 − y) / 2, p = (cos φ, y, −sin φ).
TriangleMesh cylinderSoup(int segments) {
    TriangleMesh m;
    auto corner = [&](int j, int i) {
        const float u = float(j) / float(segments), phi = 2.0f * kPi * u, y = i ? 1.0f : -1.0f;
        m.positions.emplace_back(std::cos(phi), y, -std::sin(phi));
        m.normals.emplace_back(std::cos(phi), 0.0f, -std::sin(phi));
        m.uvs.emplace_back(u, (1.0f - y) / 2.0f);
        m.indices.push_back(uint32_t(m.positions.size() - 1));
    };
    for (int j = 0; j < segments; ++j) {
        corner(j, 0), corner(j + 1, 0), corner(j + 1, 1);
        corner(j, 0), corner(j + 1, 1), corner(j, 1);
    }
    return m;
}

// (c) A curved mesh: the corners that share position, normal and uv get one tangent, orthogonal
// to the normal and along the analytic ∂p/∂u = 2π (−sin φ, 0, −cos φ) (by symmetry the averaged
// facets' chords); the per-triangle ∂p/∂u of before differs between the neighbours by the facet
// angle, 2π / segments.
TEST(GltfTangents, CurvedMeshTangentsAreSmooth) {
    const int segments = 8;
    TriangleMesh m = cylinderSoup(segments);
    const size_t before = m.positions.size();
    gltf::generateTangents(m, 0);
    EXPECT_EQ(m.positions.size(), before) << "one orientation: nothing split";
    for (size_t v = 0; v < m.positions.size(); ++v) {
        const vec4 t = tangentOf(m, v);
        const vec3 n = m.normals[v];
        const float phi = 2.0f * kPi * m.uvs[v].x;
        EXPECT_NEAR(glm::length(vec3(t)), 1.0f, 1e-5f) << v;
        EXPECT_NEAR(glm::dot(vec3(t), n), 0.0f, 1e-5f) << v;
        expectNear(vec3(t), vec3(-std::sin(phi), 0.0f, -std::cos(phi)), 1e-5f, "analytic ∂p/∂u at vertex " + std::to_string(v));
        EXPECT_EQ(t.w, 1.0f) << "N × T = +y = −∂p/∂v: unmirrored, " << v;
        for (size_t o = 0; o < v; ++o)  // welded corners: the same tangent bit for bit
            if (m.positions[o] == m.positions[v] && m.uvs[o] == m.uvs[v]) expectTangent(tangentOf(m, o), t, strCat("welded ", o, " and ", v));
    }
    // The per-triangle rule: at vertex φ = 2π/8 the two facets' ∂p/∂u are 45° apart.
    auto facetDpdu = [&](size_t tri) { return glm::normalize(m.positions[m.indices[3 * tri + 1]] - m.positions[m.indices[3 * tri]]); };
    EXPECT_LT(glm::dot(facetDpdu(0), facetDpdu(2)), std::cos(0.7f)) << "neighbouring facets' chords differ";
}

// (d) A file's TANGENT is used as it is: the quad of node "tangent" keeps the file's (0, 0, 1,
// w −1) placed by the node's 90° about y, (1, 0, 0, −1); generated ones would be ∂p/∂u turned
// the same way, (0, 0, −1, 1).
TEST(GltfTangents, AFilesTangentIsNotRegenerated) {
    const SceneDescription d = load("normal_mapped.gltf");
    const TriangleMesh& m = *d.shapes[0].mesh;  // node "tangent"
    ASSERT_EQ(m.positions.size(), 4u);
    int tangents = 0;
    for (const MeshAttribute& a : m.attributes) tangents += a.name == gltf::kTangentAttribute;
    EXPECT_EQ(tangents, 1);
    for (size_t v = 0; v < 4; ++v) {
        const vec4 t = tangentOf(m, v);
        expectNear(vec3(t), vec3(1, 0, 0), 1e-6f, "file tangent, vertex " + std::to_string(v));
        EXPECT_EQ(t.w, -1.0f);
    }
    // The scale-0 quad's material has a normal texture too, so it gets tangents; a material
    // without one would not (GltfNormalMap.TangentMappedMeshesAreNotInstanced).
    EXPECT_NE(d.shapes[2].mesh->findAttribute(gltf::kTangentAttribute), nullptr);
}

void expectUsable(const TriangleMesh& m, const std::string& what) {
    for (size_t v = 0; v < m.positions.size(); ++v) {
        const vec4 t = tangentOf(m, v);
        for (int i = 0; i < 4; ++i) ASSERT_TRUE(std::isfinite(t[i])) << what << " vertex " << v;
        EXPECT_NEAR(glm::length(vec3(t)), 1.0f, 1e-5f) << what << " vertex " << v;
        if (!m.normals.empty()) EXPECT_NEAR(glm::dot(vec3(t), glm::normalize(m.normals[v])), 0.0f, 1e-5f) << what << " vertex " << v;
        EXPECT_EQ(std::abs(t.w), 1.0f) << what << " vertex " << v;
    }
}

TriangleMesh tiltedQuad() {
    TriangleMesh m;
    const vec3 n = glm::normalize(vec3(0.3f, 1.0f, -0.2f));
    const vec3 a = glm::normalize(glm::cross(n, vec3(0, 0, 1))), b = glm::cross(n, a);
    m.positions = {-a - b, a - b, a + b, -a + b};
    m.normals = {n, n, n, n};
    m.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    m.indices = {0, 2, 1, 0, 3, 2};
    return m;
}

// (e) Degenerate UVs: all equal, collinear, missing, a missing TEXCOORD_1, a zero-area triangle
// and a mesh without normals give finite unit tangents orthogonal to N (Frame::fromNormal's), and
// a degenerate triangle's corner at a welded vertex borrows its neighbours' tangent.
TEST(GltfTangents, DegenerateUVsGiveNoNaN) {
    TriangleMesh same = tiltedQuad();
    for (vec2& uv : same.uvs) uv = vec2(0.5f);
    gltf::generateTangents(same, 0);
    expectUsable(same, "equal uvs");
    const vec3 fallback = Frame::fromNormal(same.normals[0]).s;
    expectNear(vec3(tangentOf(same, 0)), fallback, 1e-6f, "deterministic fallback");

    TriangleMesh collinear = tiltedQuad();
    collinear.uvs = {{0, 0}, {1, 1}, {2, 2}, {3, 3}};
    gltf::generateTangents(collinear, 0);
    expectUsable(collinear, "collinear uvs");

    TriangleMesh none = tiltedQuad();
    none.uvs.clear();
    gltf::generateTangents(none, 0);
    expectUsable(none, "no uvs");
    TriangleMesh noSet1 = tiltedQuad();
    gltf::generateTangents(noSet1, 1);
    expectUsable(noSet1, "no TEXCOORD_1");

    TriangleMesh noNormals = tiltedQuad();
    noNormals.normals.clear();
    noNormals.positions.push_back(noNormals.positions[0]);  // plus a zero-area triangle
    noNormals.uvs.push_back(noNormals.uvs[0]);
    noNormals.indices.insert(noNormals.indices.end(), {0, 4, 0});
    gltf::generateTangents(noNormals, 0);
    expectUsable(noNormals, "no normals, a zero-area triangle");

    // A triangle with equal uvs beside a good one, sharing vertices 0 and 2 (welded): its corners
    // there take the good triangle's tangent; its own vertex 3 (no good corner) falls back.
    TriangleMesh mixed = tiltedQuad();
    mixed.uvs[3] = mixed.uvs[0];
    mixed.uvs.push_back(mixed.uvs[0]);
    mixed.positions.push_back(mixed.positions[0]), mixed.normals.push_back(mixed.normals[0]);  // vertex 4 = vertex 0, welded
    mixed.indices = {0, 2, 1, 4, 3, 3};  // second triangle degenerate in uv (and in position)
    gltf::generateTangents(mixed, 0);
    expectUsable(mixed, "mixed");
    expectTangent(tangentOf(mixed, 4), tangentOf(mixed, 0), "a degenerate corner borrows the welded vertex's tangent");
    const vec3 dpdu = glm::normalize(mixed.positions[1] - mixed.positions[0]);
    expectNear(vec3(tangentOf(mixed, 0)), dpdu, 1e-5f, "the good triangle's ∂p/∂u");
}

}  // namespace
}  // namespace iris
