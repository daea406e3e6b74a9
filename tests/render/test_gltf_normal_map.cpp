// glTF normal and occlusion textures (§3.9.3; materials/gltf_normal_map.h, render/loader/
// gltf_material.cpp) on normal_mapped.gltf of tests/gltf/make_assets.py: three flat quads facing
// +y with one constant normal texture, with a TANGENT attribute, with tangents generated from the UVs, and
// at scale 0. The shading normal a hit gets is compared with the spec's formula written out here:
//   n' = normalize(x T + y B + z N), (x, y, z) = normalize((texel/255 · 2 − 1) · (s, s, 1)),
//   B = (N × T) · w.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "core/error.h"
#include "core/source_tree.h"
#include "materials/gltf_texture.h"
#include "materials/perturbed_frame.h"
#include "render/film.h"
#include "render/loader/gltf_loader.h"
#include "render/loader/scene_file.h"
#include "render/renderer.h"
#include "render/scene.h"
#include "tests/support/error_of.h"

namespace iris {
namespace {

std::string asset(const std::string& name) { return sourcePath("tests/data/gltf/" + name); }

std::string text(const std::string& name) {
    std::ifstream in(asset(name));
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

std::string replaced(std::string s, const std::string& from, const std::string& to) {
    const size_t at = s.find(from);
    if (at == std::string::npos) throw std::runtime_error("not found: " + from);
    return s.replace(at, from.size(), to);
}

SceneDescription fromMemory(const std::string& json, const std::string& name, int res = 16) {
    GltfOptions o;
    o.width = res;
    return loadGltfSceneFromMemory(json, name, sourcePath("tests/data/gltf"), o);
}

/// The world shading normal the material gives a ray straight down onto (x, z).
vec3 shadingNormalAt(const Scene& scene, float x, float z) {
    const std::optional<SurfaceInteraction> si = scene.intersect(Ray(vec3(x, 3.0f, z), vec3(0, -1, 0)));
    if (!si) throw std::runtime_error("missed");
    const ShadingPoint sp = shadingPointAt(*si);
    const auto* mapped = dynamic_cast<const PerturbedMaterial*>(si->material);
    if (!mapped) throw std::runtime_error("not normal-mapped");
    return sp.shading.toWorld(glm::normalize(mapped->perturbation(sp)));
}

/// The spec's formula with the asset's texel (191, 90, 223) and scale.
vec3 specNormal(const vec3& T, const vec3& N, float w, float scale) {
    const vec3 c = vec3(191, 90, 223) / 255.0f;
    const vec3 local = glm::normalize((c * 2.0f - 1.0f) * vec3(scale, scale, 1.0f));
    const vec3 B = glm::cross(N, T) * w;
    return glm::normalize(local.x * T + local.y * B + local.z * N);
}

void expectNear(const vec3& got, const vec3& want, const char* what) {
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(got[i], want[i], 2e-5f) << what << " component " << i;
}

TEST(GltfNormalMap, ShadingNormalIsTheSpecsFormula) {
    const Scene scene(loadSceneFile(asset("normal_mapped.gltf")));
    const vec3 N(0, 1, 0);
    // TANGENT (0, 0, 1, w −1), turned by the node's 90° about y to +x.
    expectNear(shadingNormalAt(scene, -2.2f, 0.3f), specNormal(vec3(1, 0, 0), N, -1.0f, 0.5f), "TANGENT given");
    // No TANGENT: the generated T = ∂p/∂u = +x (u runs along x on the quad), w = 1.
    expectNear(shadingNormalAt(scene, 0.2f, -0.4f), specNormal(vec3(1, 0, 0), N, 1.0f, 0.5f), "tangent from UVs");
    // Scale 0: the geometric normal.
    expectNear(shadingNormalAt(scene, 2.3f, 0.1f), N, "scale 0");
    // The two first differ (the handedness w), and neither is N: the map is applied.
    EXPECT_GT(glm::length(shadingNormalAt(scene, -2.2f, 0.3f) - shadingNormalAt(scene, 0.2f, -0.4f)), 0.1f);
    EXPECT_LT(shadingNormalAt(scene, 0.2f, -0.4f).y, 0.99f);
}

TEST(GltfNormalMap, TangentMappedMeshesAreNotInstanced) {
    // The TANGENT quad's mesh used by a second node: its TANGENT is placed with the mesh (an
    // instance would not turn it), so the mesh is written out twice instead of instanced ...
    const std::string json = text("normal_mapped.gltf");
    const SceneDescription twice = fromMemory(replaced(json, "\"mesh\": 1,", "\"mesh\": 0,"), "nm.gltf");
    EXPECT_EQ(twice.shapes.size(), 3u);
    EXPECT_TRUE(twice.instances.empty());
    // ... and so is the mesh without TANGENT, whose tangents are generated at import (glTF
    // §3.7.2.1, render/loader/gltf_tangents.h) and read as a TANGENT attribute ...
    const std::string computedTwice = replaced(json, "\"mesh\": 0,", "\"mesh\": 1,");
    const SceneDescription generated = fromMemory(computedTwice, "nm.gltf");
    EXPECT_EQ(generated.shapes.size(), 3u);
    EXPECT_TRUE(generated.instances.empty());
    // ... while without the normal texture (no tangents needed, none generated) it is instanced.
    const std::string unmapped = replaced(computedTwice, "\"normalTexture\": {\n    \"index\": 0,\n    \"scale\": 0.5\n   }", "\"doubleSided\": false");
    const SceneDescription inst = fromMemory(unmapped, "nm.gltf");
    EXPECT_EQ(inst.shapes.size(), 1u);
    EXPECT_EQ(inst.instances.size(), 2u);
    for (const ShapeDescription& s : inst.instances[0].group->shapes) EXPECT_EQ(s.mesh->findAttribute(gltf::kTangentAttribute), nullptr);
}

TEST(GltfNormalMap, BadNormalTexturesNameTheFileAndPath) {
    const std::string e = test::errorOf([] { loadSceneFile(asset("bad_normal_texture.gltf")); });
    EXPECT_TRUE(test::contains(e, "bad_normal_texture.gltf")) << e;
    EXPECT_TRUE(test::contains(e, "/materials/0/normalTexture/index")) << e;
    const std::string json = replaced(text("normal_mapped.gltf"), "\"scale\": 0.5", "\"scale\": 0.5, \"texCoord\": 4");
    const std::string t = test::errorOf([&] { fromMemory(json, "nm.gltf"); });
    EXPECT_TRUE(test::contains(t, "nm.gltf")) << t;
    EXPECT_TRUE(test::contains(t, "/materials/0/normalTexture/texCoord")) << t;
}

TEST(GltfOcclusion, IsCheckedNotWarnedAndDoesNotChangeTheImage) {
    const std::string plain = text("textured.gltf");
    const std::string occluded = replaced(plain, "\"alphaMode\"", "\"occlusionTexture\": {\"index\": 0, \"strength\": 1.0}, \"alphaMode\"");
    testing::internal::CaptureStderr();
    const SceneDescription a = fromMemory(plain, "t.gltf"), b = fromMemory(occluded, "t.gltf");
    const std::string err = testing::internal::GetCapturedStderr();
    EXPECT_EQ(err, "") << "no warning for an occlusion texture";
    RenderOptions opt;
    opt.spp = 8;
    opt.seed = 4;
    Film fa(a.camera.width, a.camera.height), fb(b.camera.width, b.camera.height);
    Renderer(Scene(a), opt).render(fa);
    Renderer(Scene(b), opt).render(fb);
    for (int y = 0; y < fa.height(); ++y)
        for (int x = 0; x < fa.width(); ++x)
            for (int c = 0; c < 3; ++c) ASSERT_EQ(fa.pixel(x, y)[c], fb.pixel(x, y)[c]) << x << "," << y;
    // Checked: an occlusion texture that does not exist is an error naming the path.
    const std::string bad = replaced(plain, "\"alphaMode\"", "\"occlusionTexture\": {\"index\": 7}, \"alphaMode\"");
    const std::string e = test::errorOf([&] { fromMemory(bad, "occ.gltf"); });
    EXPECT_TRUE(test::contains(e, "occ.gltf")) << e;
    EXPECT_TRUE(test::contains(e, "/materials/0/occlusionTexture/index")) << e;
}

}  // namespace
}  // namespace iris
