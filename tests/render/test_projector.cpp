// The `projector` emitter (render/lights/projector_light.cpp) as Mitsuba 3 defines it: the
// reciprocal of the perspective camera (the texel a camera pixel sees is the texel the projector
// sends along that pixel's ray, for non-square images too), irradiance π·scale·E on the plane
// z = 1 whatever the angle, nothing outside the image or behind, a lit diffuse wall of albedo ρ
// rendered as ρ·scale·E in both modes, and the errors of a wrong projector.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "core/io/image.h"
#include "render/lights/light.h"
#include "spectral/color_space.h"
#include "render/loader/scene_loader.h"
#include "render/sensors/perspective.h"
#include "spectral/wavelengths.h"
#include "tests/support/error_of.h"
#include "tests/support/one_emitter.h"
#include "tests/support/image_mean.h"

namespace iris {
namespace {

const SampledWavelengths kRGB = SampledWavelengths::rgb(defaultChannelWavelengths());

/// Irradiance L·cos θ that the projector (axis +z from the origin unless to_world says otherwise)
/// delivers at p onto a surface facing it along −z, divided by π, in RGB channel c.
float irradianceOverPi(const Light& l, const vec3& p, int c = 1) {
    const auto s = l.sampleLi(p, vec2(0.5f), kRGB);
    return s ? s->L[c] * -s->wi.z / kPi : 0.0f;
}

TEST(Projector, AConstantImageGivesConstantIrradianceOnThePlaneZ1) {
    const LightPtr l = test::loadOneEmitter("projector", "<float name=\"fov\" value=\"90\"/><float name=\"irradiance\" value=\"0.8\"/><float name=\"scale\" value=\"2\"/>");
    for (const vec2 xy : {vec2(0.0f), vec2(0.9f, 0.0f), vec2(-0.7f, 0.6f), vec2(0.99f, -0.99f)})
        EXPECT_NEAR(irradianceOverPi(*l, vec3(xy, 1.0f)), 1.6f, 1e-5f) << xy.x << " " << xy.y;
    // Point-light falloff along a ray: at z = 3 a ninth of it.
    EXPECT_NEAR(irradianceOverPi(*l, vec3(0.3f, 0.6f, 3.0f)), 1.6f / 9.0f, 1e-5f);
    // fov 90°: the image spans |x|, |y| ≤ z; beyond it and behind the projector nothing arrives.
    EXPECT_EQ(irradianceOverPi(*l, vec3(1.05f, 0.0f, 1.0f)), 0.0f);
    EXPECT_EQ(irradianceOverPi(*l, vec3(0.0f, -1.05f, 1.0f)), 0.0f);
    EXPECT_EQ(irradianceOverPi(*l, vec3(0.0f, 0.0f, -1.0f)), 0.0f);
}

TEST(Projector, SendsAlongEachCameraRayThePixelThatCameraSees) {
    // A 4 × 2 image of distinct texels; a perspective camera with the same fov and a 4 × 2 film,
    // at the projector's place: the ray through pixel (i, j)'s centre receives texel (i, j).
    Image img(4, 2, 3);
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 4; ++x)
            for (int c = 0; c < 3; ++c) img.at(x, y, c) = 0.1f + 0.1f * float(x + 4 * y);
    const std::string path = ::testing::TempDir() + "iris_projector_4x2.exr";
    writeEXR(path, img);
    const std::string frame = "<transform name=\"to_world\"><lookat origin=\"1, 2, 3\" target=\"1.5, 1, -2\" up=\"0, 1, 0\"/></transform>";
    for (const std::string fovAxis : {"x", "y", "diagonal"}) {
        const LightPtr l = test::loadOneEmitter("projector", "<float name=\"fov\" value=\"35\"/><string name=\"fov_axis\" value=\"" + fovAxis + "\"/>" + frame +
                                         "<texture name=\"irradiance\" type=\"bitmap\"><string name=\"filename\" value=\"" + path +
                                         "\"/><string name=\"filter_type\" value=\"nearest\"/></texture>");
        const FovAxis axis = fovAxis == "x" ? FovAxis::X : fovAxis == "y" ? FovAxis::Y : FovAxis::Diagonal;
        mat4 toWorld = glm::inverse(glm::lookAt(vec3(1, 2, 3), vec3(1.5f, 1, -2), vec3(0, 1, 0)));
        toWorld = toWorld * glm::scale(mat4(1.0f), vec3(-1, 1, -1));  // Mitsuba's lookat: +z forward, +x left
        const PerspectiveSensor cam(toWorld, 35.0f, axis, FilmSize{4, 2});
        for (int y = 0; y < 2; ++y)
            for (int x = 0; x < 4; ++x) {
                const Ray r = cam.generateRay(vec2(x + 0.5f, y + 0.5f));
                const vec3 p = r.o + 2.5f * r.d;
                const auto s = l->sampleLi(p, vec2(0.5f), kRGB);
                ASSERT_TRUE(s.has_value()) << fovAxis << " " << x << "," << y;
                EXPECT_NEAR(glm::dot(s->wi, r.d), -1.0f, 1e-5f);
                // L = π E / (z² cos θ) with z = 2.5 cos θ.
                const float cosTheta = glm::dot(r.d, glm::normalize(vec3(0.5f, -1.0f, -5.0f)));
                const float e = s->L[0] * std::pow(2.5f * cosTheta, 2.0f) * cosTheta / kPi;
                EXPECT_NEAR(e, img.at(x, y, 0), 1e-4f) << fovAxis << " pixel " << x << "," << y;
            }
    }
    std::remove(path.c_str());
}

test::ImageMean wallMean(const std::string& projectorParams, bool rgb, int channel, int spp = 4) {
    // A diffuse wall of albedo 0.5 at distance 2 facing a camera and a projector at the same place
    // (camera fov 30°, projector 50°: every pixel is lit). Radiance ρ/π · π·scale·E·(2²/z²) at z = 2.
    const std::string xml = R"(<scene version="3.0.0">
  <integrator type="direct"/>
  <sensor type="perspective"><float name="fov" value="30"/>
    <transform name="to_world"><lookat origin="0, 0, 0" target="0, 0, 2" up="0, 1, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="6"/><integer name="height" value="4"/></film>
  </sensor>
  <shape type="rectangle"><transform name="to_world"><scale value="10"/><translate z="2"/></transform>
    <boolean name="flip_normals" value="true"/><bsdf type="diffuse"><float name="reflectance" value="0.5"/></bsdf></shape>
  <emitter type="projector"><float name="fov" value="50"/>
    <transform name="to_world"><lookat origin="0, 0, 0" target="0, 0, 1" up="0, 1, 0"/></transform>
)" + projectorParams + "</emitter></scene>";
    return test::imageMean(test::renderXml(xml, 6, 4, spp, 5, rgb), channel);
}

double wallY(const std::string& projectorParams, bool rgb) { return wallMean(projectorParams, rgb, 1).mean; }

TEST(Projector, LightsADiffuseWallWithRhoTimesScaleTimesE) {
    const std::string params = "<float name=\"irradiance\" value=\"0.2\"/><float name=\"scale\" value=\"1.5\"/>";
    // The wall at z = 2 gets irradiance π·1.5·0.2/4 and reflects 0.5/π of it: 0.0375.
    for (const bool rgb : {true, false}) {
        const double y = wallY(params, rgb);
        EXPECT_NEAR(y, 0.0375, 2e-4) << (rgb ? "rgb" : "spectral");
        // The test can fail: without Mitsuba's π factor the wall would be 0.0375/π.
        EXPECT_GT(std::abs(y - 0.0375 / kPi), 0.01);
    }
}

TEST(Projector, AColouredTextureLightsAWhiteWallAlikeInBothModes) {
    // Mitsuba 3 reads the texture with props.texture (a bitmap is a reflectance-upsampled colour in
    // spectral variants) and multiplies by D65·scale: on a white wall the spectral render is the
    // RGB one. A reference whose two variants differ there (issue 33: 1.19/0.95/0.91) is the odd one out.
    const std::string path = testing::TempDir() + "projector_colour.exr";
    Image img(2, 2, 3);
    for (int i = 0; i < 4; ++i) img.pixels[3 * i] = 0.8f, img.pixels[3 * i + 1] = 0.3f, img.pixels[3 * i + 2] = 0.1f;
    writeEXR(path, img);
    const std::string params = "<texture type=\"bitmap\" name=\"irradiance\"><string name=\"filename\" value=\"" + path +
                               "\"/></texture><float name=\"scale\" value=\"1.5\"/>";
    // The RGB-mode film holds linear Rec.709, the spectral one CIE XYZ: compare in XYZ.
    dvec3 rgb;
    for (int c = 0; c < 3; ++c) {
        rgb[c] = wallMean(params, true, c).mean;
        EXPECT_NEAR(rgb[c], 0.5 * 1.5 * (c == 0 ? 0.8 : c == 1 ? 0.3 : 0.1) / 4, 1e-4) << "channel " << c;
    }
    const dvec3 xyz = linearRec709ToXYZ(rgb);
    for (int c = 0; c < 3; ++c) {
        const test::ImageMean spectral = wallMean(params, false, c, 256);
        EXPECT_NEAR(spectral.mean, xyz[c], 5 * spectral.stderr_ + 2e-3 * xyz[c]) << "XYZ channel " << c;
    }
    std::remove(path.c_str());
}

TEST(Projector, WrongProjectorsAreRefusedWithTheirLine) {
    const auto err = [](const std::string& body) { return test::sceneError("<emitter type=\"projector\">\n" + body + "</emitter>"); };
    const auto has = test::contains;
    const std::string missing = err("<float name=\"fov\" value=\"40\"/>\n");
    EXPECT_TRUE(has(missing, "<string>:2:") && has(missing, "irradiance")) << missing;
    const std::string scale = err("<float name=\"irradiance\" value=\"1\"/>\n<float name=\"scale\" value=\"-2\"/>\n");
    EXPECT_TRUE(has(scale, "<string>:4: projector: scale must be finite and >= 0")) << scale;
    const std::string fov = err("<float name=\"irradiance\" value=\"1\"/>\n<float name=\"fov\" value=\"180\"/>\n");
    EXPECT_TRUE(has(fov, "<string>:4: fov must be in (0, 180) degrees")) << fov;
    const std::string both = err("<float name=\"irradiance\" value=\"1\"/>\n<float name=\"fov\" value=\"30\"/>\n<string name=\"focal_length\" value=\"35mm\"/>\n");
    EXPECT_TRUE(has(both, "<string>:5: give either fov or focal_length, not both")) << both;
    EXPECT_EQ(err("<float name=\"irradiance\" value=\"1\"/>\n<string name=\"focal_length\" value=\"35mm\"/>\n"), "");
}

}  // namespace
}  // namespace iris
