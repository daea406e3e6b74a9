// The glTF 2.0 importer (render/loader/gltf_*) on the assets of tests/gltf/make_assets.py:
// meshes, hierarchy, instancing, modes, cameras, lights, alpha, the XML <shape type="gltf">,
// spectral and RGB renders, and hostile files refused with the file and JSON path named.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <typeinfo>

#include <unistd.h>

#include "core/error.h"
#include "core/source_tree.h"
#include "render/film.h"
#include "render/loader/scene_file.h"
#include "render/renderer.h"
#include "render/scene.h"
#include "tests/support/error_of.h"
#include "tests/support/image_mean.h"

namespace iris {
namespace {

std::string asset(const std::string& name) { return sourcePath("tests/data/gltf/" + name); }

size_t triangles(const SceneDescription& s) {
    size_t n = 0;
    for (const ShapeDescription& sh : s.shapes) n += sh.mesh ? sh.mesh->triangleCount() : 0;
    return n;
}

TEST(GltfLoader, BasicSceneHasItsMeshesCameraAndLights) {
    const SceneDescription s = loadSceneFile(asset("basic.gltf"));
    ASSERT_EQ(s.shapes.size(), 2u);
    EXPECT_EQ(s.lights.size(), 2u);  // a point and a directional light, no default environment
    EXPECT_EQ(s.camera.width, 512);
    EXPECT_EQ(s.camera.height, 341);  // aspectRatio 1.5
    // The ball sits at y = 1 (node translation): its vertices span y ∈ [0, 2].
    float lo = 1e9f, hi = -1e9f;
    for (const vec3& p : s.shapes[1].mesh->positions) lo = std::min(lo, p.y), hi = std::max(hi, p.y);
    EXPECT_NEAR(lo, 0.0f, 1e-5f);
    EXPECT_NEAR(hi, 2.0f, 1e-5f);
    EXPECT_EQ(s.shapes[1].mesh->normals.size(), s.shapes[1].mesh->positions.size());
    EXPECT_EQ(s.shapes[1].mesh->uvs.size(), s.shapes[1].mesh->positions.size());
}

TEST(GltfLoader, GlbAndExternalBufferGiveTheSameMeshes) {
    const SceneDescription a = loadSceneFile(asset("basic.gltf"));
    for (const char* other : {"basic.glb", "basic_external.gltf"}) {
        const SceneDescription b = loadSceneFile(asset(other));
        ASSERT_EQ(a.shapes.size(), b.shapes.size()) << other;
        for (size_t i = 0; i < a.shapes.size(); ++i) {
            EXPECT_EQ(a.shapes[i].mesh->positions, b.shapes[i].mesh->positions) << other;
            EXPECT_EQ(a.shapes[i].mesh->indices, b.shapes[i].mesh->indices) << other;
        }
    }
}

TEST(GltfLoader, AMeshUsedByManyNodesIsInstanced) {
    const SceneDescription s = loadSceneFile(asset("instanced.gltf"));
    EXPECT_TRUE(s.shapes.empty());
    ASSERT_EQ(s.instances.size(), 4u);
    for (const InstanceDescription& i : s.instances) EXPECT_EQ(i.group, s.instances[0].group) << "one group shared";
    // The children compose with the parent's translation (0, 0.5, 0): TRS order T · R · S.
    EXPECT_NEAR(s.instances[0].toWorld[3].x, -1.5f, 1e-6f);
    EXPECT_NEAR(s.instances[0].toWorld[3].y, 0.5f, 1e-6f);
    EXPECT_NEAR(s.instances[2].toWorld[1].y, 2.0f, 1e-6f);  // scale y 1 + 0.5·2
    EXPECT_NEAR(s.instances[3].toWorld[3].y, 2.0f, 1e-6f);  // the node given as a matrix
}

TEST(GltfLoader, StripsAndFansBecomeTrianglesFacingTheirNormals) {
    const SceneDescription s = loadSceneFile(asset("strips_fans.gltf"));
    ASSERT_EQ(s.shapes.size(), 2u);
    for (const ShapeDescription& sh : s.shapes) {
        const TriangleMesh& m = *sh.mesh;
        ASSERT_EQ(m.triangleCount(), 2u) << sh.name;
        for (size_t t = 0; t < 2; ++t) {
            const vec3 a = m.positions[m.indices[3 * t]], b = m.positions[m.indices[3 * t + 1]], c = m.positions[m.indices[3 * t + 2]];
            EXPECT_GT(glm::cross(b - a, c - a).y, 0.0f) << sh.name << " triangle " << t << " is wound against its normal";
        }
    }
}

TEST(GltfLoader, AlphaMaskCutsTheTexturedQuad) {
    // The 2×2 texture has alpha 40/255 in its top-right texel: with MASK 0.5 those parts are holes.
    SceneDescription s = loadSceneFile(asset("textured.gltf"), {{"res", "32"}, {"spp", "8"}});
    ASSERT_EQ(s.shapes.size(), 1u);
    Arena arena;
    SampledWavelengths wl = SampledWavelengths::rgb(defaultChannelWavelengths());
    auto opacityAt = [&](vec2 uv) {
        ShadingPoint sp;
        sp.tex.uv = uv;
        const BSDF* b = s.shapes[0].material->getBSDF(sp, wl, arena);
        return b->eval(vec3(0, 0, 1), vec3(0, 0.6f, 0.8f), TransportMode::Radiance)[0];
    };
    // KHR_texture_transform scale 2: uv (0.3, 0.1) → (0.6, 0.2), the top-right texel (alpha 40).
    EXPECT_EQ(opacityAt(vec2(0.3f, 0.1f)), 0.0f);
    EXPECT_GT(opacityAt(vec2(0.1f, 0.1f)), 0.0f);  // top-left, red, opaque
}

TEST(GltfLoader, ABadTmpdirIsNamedWhenAnEmbeddedImageIsDecoded) {
    // An embedded image is decoded through a temporary file under $TMPDIR. A TMPDIR that is not a
    // folder made std::filesystem::temp_directory_path throw ("filesystem error:
    // temp_directory_path", naming neither the scene nor the variable); now the error names both.
    const std::string file = (std::filesystem::temp_directory_path() / ("iris_gltf_tmpdir_" + std::to_string(::getpid()))).string();
    std::ofstream(file) << "not a folder";
    const char* old = std::getenv("TMPDIR");
    const std::optional<std::string> saved = old ? std::optional<std::string>(old) : std::nullopt;
    ::setenv("TMPDIR", file.c_str(), 1);
    std::string message;
    try {
        loadSceneFile(asset("textured.gltf"), {{"res", "32"}, {"spp", "8"}});
    } catch (const Error& e) {
        message = e.what();
    }
    saved ? ::setenv("TMPDIR", saved->c_str(), 1) : ::unsetenv("TMPDIR");
    std::filesystem::remove(file);
    EXPECT_NE(message.find("textured.gltf"), std::string::npos) << message;
    EXPECT_NE(message.find("'" + file + "' ($TMPDIR)"), std::string::npos) << message;
}

TEST(GltfLoader, ASceneWithoutLightsGetsTheDefaultEnvironment) {
    const SceneDescription s = loadSceneFile(asset("strips_fans.gltf"));
    ASSERT_EQ(s.lights.size(), 1u);
    // An emitting mesh lights a scene: no environment is added (extensions.gltf has one emissive
    // sphere and one directional light).
    const SceneDescription e = loadSceneFile(asset("extensions.gltf"));
    EXPECT_EQ(e.lights.size(), 1u);
}

TEST(GltfLoader, EnvmapOptionReplacesTheDefaultEnvironment) {
    // strips_fans.gltf has no light: by default one constant environment; with envmap, the map
    // instead (an envmap light, whose Le varies over directions where the constant's does not).
    const SceneDescription plain = loadSceneFile(asset("strips_fans.gltf"));
    const SceneDescription lit = loadSceneFile(asset("strips_fans.gltf"), {{"envmap", sourcePath("scenes/textures/museum.exr")}});
    ASSERT_EQ(plain.lights.size(), 1u);
    ASSERT_EQ(lit.lights.size(), 1u);
    EXPECT_NE(typeid(*plain.lights[0]).name(), typeid(*lit.lights[0]).name());
    EXPECT_TRUE(test::contains(test::errorOf([] { loadSceneFile(asset("strips_fans.gltf"), {{"envmap", "no_such_map.exr"}}); }),
                               "no_such_map.exr"));
}

TEST(GltfLoader, CameraIsChosenByName) {
    EXPECT_NO_THROW(loadSceneFile(asset("basic.gltf"), {{"camera", "main"}}));
    EXPECT_NO_THROW(loadSceneFile(asset("basic.gltf"), {{"camera", "main_node"}}));
    const std::string e = test::errorOf([] { loadSceneFile(asset("basic.gltf"), {{"camera", "nope"}}); });
    EXPECT_TRUE(test::contains(e, "basic.gltf")) << e;
    EXPECT_TRUE(test::contains(e, "'nope'")) << e;
    EXPECT_TRUE(test::contains(test::errorOf([] { loadSceneFile(asset("basic.gltf"), {{"bogus", "1"}}); }), "bogus"));
}

TEST(GltfLoader, XmlShapePlacesTheFileInAScene) {
    const std::string xml = R"(<scene version="3.0.0">
        <shape type="gltf"><string name="filename" value=")" + asset("basic.gltf") + R"("/>
            <transform name="to_world"><translate x="10"/></transform></shape>
        <emitter type="constant"/></scene>)";
    const SceneDescription s = loadSceneFromString(xml, sourceDir());
    ASSERT_EQ(s.shapes.size(), 2u);
    EXPECT_EQ(s.lights.size(), 3u);  // the file's two and the constant
    float lo = 1e9f;
    for (const vec3& p : s.shapes[1].mesh->positions) lo = std::min(lo, p.x);
    EXPECT_NEAR(lo, 9.0f, 1e-4f);
    const std::string e = test::sceneError(R"(<shape type="gltf"><string name="filename" value="nothing.gltf"/></shape>)");
    EXPECT_TRUE(test::contains(e, "nothing.gltf")) << e;
}

TEST(GltfLoader, RendersInSpectralAndRgbMode) {
    for (bool rgb : {false, true}) {
        const Scene scene(loadSceneFile(asset("iridescence_metallic_spheres.gltf"), {{"res", "24"}}));
        RenderOptions opt;
        opt.rgbMode = rgb;
        opt.spp = 4;
        opt.seed = 3;
        Film film(scene.description().camera.width, scene.description().camera.height);
        Renderer(scene, opt).render(film);
        const test::ImageMean m = test::imageMean(film, 1);
        EXPECT_TRUE(std::isfinite(m.mean));
        EXPECT_GT(m.mean, 0.05) << (rgb ? "rgb" : "spectral");
    }
}

struct Hostile {
    const char* file;
    const char* expect;  // part of the message: the JSON path or the problem
};

TEST(GltfLoader, HostileFilesAreRefusedWithFileAndPath) {
    const Hostile cases[] = {
        {"bad_truncated.glb", "cannot read glTF"},
        {"bad_accessor_range.gltf", "/accessors/0"},
        {"bad_buffer_view.gltf", "/bufferViews/0"},
        {"bad_huge_count.gltf", "/accessors/0"},
        {"bad_uri.gltf", "exist.bin"},
        {"bad_index.gltf", "indices accessor"},  // tinygltf's own check (its messages name no JSON path)
        {"required_unsupported.gltf", "/extensionsRequired/0"},
        {"bad_cycle.gltf", "/nodes/0/children/0"},
        {"bad_missing_texture.gltf", "missing.png"},
        {"bad_normal_texture.gltf", "/materials/0/normalTexture/index"},
        {"bad_volume_distance.gltf", "/materials/0/extensions/KHR_materials_volume/attenuationDistance"},
        {"bad_volume_color.gltf", "/materials/0/extensions/KHR_materials_volume/attenuationColor/1"},
    };
    for (const Hostile& h : cases) {
        const std::string e = test::errorOf([&] { loadSceneFile(asset(h.file)); });
        EXPECT_TRUE(test::contains(e, h.file)) << h.file << ": " << e;
        EXPECT_TRUE(test::contains(e, h.expect)) << h.file << ": " << e;
    }
}

// The CI fuzzer's finding (crash-26427ef9...): a mangled data URI ("data:a1.QAAA...", thousands of
// characters) is a file name the file system refuses with ENAMETOOLONG. std::filesystem's
// throwing overload turned that into a filesystem_error, which no reader catches; it must be
// refused like any missing buffer, with the file named.
TEST(GltfLoader, AFileNameTooLongForTheFileSystemIsAMissingBuffer) {
    const std::string uri = "data:a1." + std::string(5000, 'A');
    const std::string path = (std::filesystem::temp_directory_path() / "iris_gltf_long_uri.gltf").string();
    {
        std::ofstream f(path);
        f << R"({"asset": {"version": "2.0"}, "buffers": [{"byteLength": 12, "uri": ")" << uri << R"("}]})";
    }
    const std::string e = test::errorOf([&] { loadSceneFile(path); });
    std::remove(path.c_str());
    EXPECT_TRUE(test::contains(e, "iris_gltf_long_uri.gltf")) << e;
    EXPECT_FALSE(test::contains(e, "filesystem error")) << e;
}

TEST(GltfLoader, UnsupportedUsedExtensionsAreAWarning) {
    testing::internal::CaptureStderr();
    const SceneDescription s = loadSceneFile(asset("warn_used.gltf"));
    const std::string err = testing::internal::GetCapturedStderr();
    EXPECT_EQ(s.shapes.size(), 2u);
    EXPECT_TRUE(test::contains(err, "EXT_lights_ies, KHR_materials_anisotropy")) << err;
    EXPECT_TRUE(test::contains(err, "warn_used.gltf")) << err;
}

}  // namespace
}  // namespace iris
