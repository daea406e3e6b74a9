// KHR_materials_volume (render/loader/gltf_volume.h, materials/gltf_pbr_bsdf.h) on the slab of
// tests/gltf/make_assets.py: a smooth glass slab (ior 1.5, white base, transmission 1) of thickness
// d = 0.5 in front of an emitter of radiance 1, seen at normal incidence. The closed form of a slab
// with interface reflectance R and internal transmittance τ (every internal reflection summed):
//   T = (1 − R)² τ / (1 − R² τ²),  R = ((ior − 1)/(ior + 1))² (Schlick at normal incidence),
//   τ = exp(−σ_a d), σ_a = −ln(attenuationColor) / attenuationDistance (the README's Beer's law).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "core/error.h"
#include "core/source_tree.h"
#include "render/film.h"
#include "render/integrator.h"
#include "render/loader/gltf_loader.h"
#include "render/loader/scene_file.h"
#include "render/renderer.h"
#include "render/scene.h"
#include "tests/support/error_of.h"
#include "tests/support/image_mean.h"

namespace iris {
namespace {

std::string asset(const std::string& name) { return sourcePath("tests/data/gltf/" + name); }

std::string slabText() {
    std::ifstream in(asset("volume_slab.gltf"));
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

/// The slab file with `from` (a unique piece of its JSON) replaced by `to`.
std::string slabWith(const std::string& from, const std::string& to) {
    std::string s = slabText();
    const size_t at = s.find(from);
    if (at == std::string::npos || s.find(from, at + 1) != std::string::npos) throw std::runtime_error("not unique: " + from);
    return s.replace(at, from.size(), to);
}

SceneDescription load(const std::string& json, int res = 16, int spp = 16) {
    GltfOptions o;
    o.width = res;
    o.spp = spp;
    return loadGltfSceneFromMemory(json, "slab.gltf", sourcePath("tests/data/gltf"), o);
}

Film render(const SceneDescription& d, bool rgb, int spp, uint64_t seed) {
    const Scene scene(d);
    RenderOptions opt;
    opt.rgbMode = rgb;
    opt.spp = spp;
    opt.seed = seed;
    opt.threads = 2;
    Film film(d.camera.width, d.camera.height);
    Renderer(scene, opt).render(film);
    return film;
}

/// The closed form above for one channel.
double slabTransmission(double color, double distance, double thickness, double ior = 1.5) {
    const double R = std::pow((ior - 1) / (ior + 1), 2);
    const double tau = std::exp(std::log(color) / distance * thickness);
    return (1 - R) * (1 - R) * tau / (1 - R * R * tau * tau);
}

constexpr double kThickness = 0.5, kDistance = 1.0;
const double kColor[3] = {0.8, 0.5, 0.2};  // the asset's attenuationColor

TEST(GltfVolume, SlabTransmissionIsFresnelTimesBeerLambert) {
    const Film film = render(loadSceneFile(asset("volume_slab.gltf"), {{"res", "24"}}), true, 256, 7);
    for (int c = 0; c < 3; ++c) {
        const test::ImageMean m = test::imageMean(film, c);
        const double expect = slabTransmission(kColor[c], kDistance, kThickness);
        EXPECT_NEAR(m.mean, expect, 4 * m.stderr_ + 1e-3) << "channel " << c << " ± " << m.stderr_;
        // The test can tell the physics apart: without the medium's absorption, or with the
        // interfaces ignored (Beer-Lambert alone), the mean is many standard errors away.
        EXPECT_GT(std::abs(m.mean - slabTransmission(1.0, kDistance, kThickness)), 8 * m.stderr_) << "channel " << c;
        EXPECT_GT(std::abs(m.mean - std::pow(kColor[c], kThickness / kDistance)), 8 * m.stderr_) << "channel " << c;
    }
}

TEST(GltfVolume, SpectralModeUpsamplesAGreyAttenuationExactly) {
    // A grey σ_a upsamples to a flat spectrum: the spectral render meets the same closed form.
    const SceneDescription d = load(slabWith("0.8,\n      0.5,\n      0.2", "0.5, 0.5, 0.5"), 24);
    const Film film = render(d, false, 256, 11);
    const test::ImageMean m = test::imageMean(film, 1);
    EXPECT_NEAR(m.mean, slabTransmission(0.5, kDistance, kThickness), 4 * m.stderr_ + 2e-3) << "± " << m.stderr_;
}

TEST(GltfVolume, InstancedSlabsEachBoundTheirMedium) {
    // The slab's mesh used by a second node 0.6 behind the first: one shape group, two instances,
    // the medium in the group's shape. Two slabs in series with the light reflected between them:
    // T² / (1 − R_s²), R_s = R + (1 − R)² R τ² / (1 − R² τ²).
    // A node inserted first (so every node index moves by one) and the scene listing all four.
    std::string json = slabWith("\"nodes\": [\n  {", "\"nodes\": [\n  {\"mesh\": 0, \"translation\": [0, 0, -0.6]}, {");
    const size_t list = json.find("0,\n    1,\n    2\n   ]");
    ASSERT_NE(list, std::string::npos);
    json.replace(list, std::string("0,\n    1,\n    2\n   ]").size(), "0, 1, 2, 3]");
    const SceneDescription two = load(json, 24);
    ASSERT_EQ(two.instances.size(), 2u);
    ASSERT_EQ(two.instances[0].group->shapes.size(), 1u);
    EXPECT_TRUE(two.instances[0].group->shapes[0].interior);
    const Film film = render(two, true, 256, 13);
    const double R = 0.04;
    for (int c = 0; c < 3; ++c) {
        const double tau = std::pow(kColor[c], kThickness / kDistance);
        const double T = slabTransmission(kColor[c], kDistance, kThickness);
        const double Rs = R + (1 - R) * (1 - R) * R * tau * tau / (1 - R * R * tau * tau);
        const test::ImageMean m = test::imageMean(film, c);
        EXPECT_NEAR(m.mean, T * T / (1 - Rs * Rs), 4 * m.stderr_ + 1e-3) << "channel " << c << " ± " << m.stderr_;
    }
}

TEST(GltfVolume, TheSlabBoundsAMediumRenderedByVolpath) {
    const SceneDescription d = loadSceneFile(asset("volume_slab.gltf"));
    ASSERT_EQ(d.shapes.size(), 2u);
    EXPECT_TRUE(d.shapes[0].interior) << "the slab's absorbing medium";
    EXPECT_FALSE(d.shapes[1].interior);
    EXPECT_EQ(d.integrator->type(), "volpath");
    // attenuationColor 1 absorbs nothing: refraction only, no medium, the default integrator.
    // Nor does an infinite attenuationDistance (the default).
    for (const auto& [from, to] : {std::pair{"\"attenuationDistance\": 1.0,", ""},
                                   std::pair{"0.8,\n      0.5,\n      0.2", "1, 1, 1"}}) {
        const SceneDescription clear = load(slabWith(from, to));
        EXPECT_FALSE(clear.shapes[0].interior) << to;
        EXPECT_EQ(clear.integrator->type(), "path") << to;
    }
}

TEST(GltfVolume, ThicknessZeroIsThinWalledAsWithoutTheExtension) {
    const std::string volume = "\"KHR_materials_volume\": {";
    const SceneDescription zero = load(slabWith("\"thicknessFactor\": 0.5", "\"thicknessFactor\": 0"));
    // The same material without the extension (renamed to an unknown key of the material's extensions).
    const SceneDescription none = load(slabWith(volume, "\"EXT_not_read\": {"));
    EXPECT_FALSE(zero.shapes[0].interior);
    for (bool rgb : {true, false}) {
        const Film a = render(zero, rgb, 8, 5), b = render(none, rgb, 8, 5);
        for (int y = 0; y < a.height(); ++y)
            for (int x = 0; x < a.width(); ++x)
                for (int c = 0; c < 3; ++c) ASSERT_EQ(a.pixel(x, y)[c], b.pixel(x, y)[c]) << x << "," << y << " rgb " << rgb;
    }
    // Thin-walled: the back face is culled (doubleSided false), one interface transmits 1 − R.
    const test::ImageMean m = test::imageMean(render(zero, true, 64, 3), 0);
    EXPECT_NEAR(m.mean, 0.96, 4 * m.stderr_ + 1e-3);
}

TEST(GltfVolume, BadParametersNameTheFileAndJsonPath) {
    const std::string base = "/materials/0/extensions/KHR_materials_volume";
    for (const auto& [file, path] : {std::pair{"bad_volume_distance.gltf", base + "/attenuationDistance"},
                                     std::pair{"bad_volume_color.gltf", base + "/attenuationColor/1"}}) {
        const std::string e = test::errorOf([&] { loadSceneFile(asset(file)); });
        EXPECT_TRUE(test::contains(e, file)) << e;
        EXPECT_TRUE(test::contains(e, path)) << e;
    }
    const std::pair<std::string, std::string> inMemory[] = {
        {"\"attenuationDistance\": -2.0", base + "/attenuationDistance"},
        {"\"attenuationDistance\": \"far\"", base + "/attenuationDistance"},
        {"\"thicknessFactor\": -1", base + "/thicknessFactor"},
        {"\"thicknessTexture\": {\"index\": 3}", base + "/thicknessTexture/index"},
    };
    for (const auto& [json, path] : inMemory) {
        const std::string e = test::errorOf([&] { load(slabWith("\"attenuationDistance\": 1.0", json + ", \"y\": 1")); });
        EXPECT_TRUE(test::contains(e, "slab.gltf")) << json << ": " << e;
        EXPECT_TRUE(test::contains(e, path)) << json << ": " << e;
    }
}

TEST(GltfVolume, XmlSceneNeedsVolpathAndScalesTheAttenuationDistance) {
    const std::string shape = R"(<shape type="gltf"><string name="filename" value=")" + asset("volume_slab.gltf") + R"("/></shape>)";
    const std::string e = test::sceneError(shape);
    EXPECT_TRUE(test::contains(e, "volpath")) << e;
    const SceneDescription s =
        loadSceneFromString(R"(<scene version="3.0.0"><integrator type="volpath"/>)" + shape + "</scene>", sourceDir());
    ASSERT_TRUE(s.shapes[0].interior);
    // σ_a = −ln(c)/d in glTF units; placed at twice the size, the distance doubles in scene units.
    const std::string scaled = R"(<shape type="gltf"><string name="filename" value=")" + asset("volume_slab.gltf") +
                               R"("/><transform name="to_world"><scale value="2"/></transform></shape>)";
    const SceneDescription big =
        loadSceneFromString(R"(<scene version="3.0.0"><integrator type="volpath"/>)" + scaled + "</scene>", sourceDir());
    ASSERT_TRUE(big.shapes[0].interior);
    const SampledWavelengths wl = SampledWavelengths::rgb(defaultChannelWavelengths());
    const MediumCoefficients one = s.shapes[0].interior->coefficients(vec3(0.0f), wl);
    const MediumCoefficients two = big.shapes[0].interior->coefficients(vec3(0.0f), wl);
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(one.sigmaT[c], -std::log(kColor[c]) / kDistance, 1e-5) << c;
        EXPECT_NEAR(two.sigmaT[c], -std::log(kColor[c]) / (2 * kDistance), 1e-5) << c;
        EXPECT_EQ(one.sigmaS[c], 0.0f) << "purely absorbing";
    }
}

}  // namespace
}  // namespace iris
