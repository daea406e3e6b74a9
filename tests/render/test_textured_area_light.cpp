// Area emitters with a textured `radiance` (Mitsuba's area emitter over the shape's uv;
// render/lights/area_light.cpp): the radiance seen at a hit and the radiance of a light sample are
// the texture at that point's uv, on meshes, spheres and cylinders; and a floor lit by a
// checkerboard rectangle receives what four constant quads of its colours give (a checkerboard with
// its colours swapped does not).
#include <gtest/gtest.h>

#include "core/rng.h"
#include "materials/material.h"
#include "render/film.h"
#include "render/lights/area_light.h"
#include "render/loader/scene_loader.h"
#include "render/renderer.h"
#include "render/scene.h"
#include "tests/support/image_mean.h"

namespace iris {
namespace {

const SampledWavelengths kRGB = SampledWavelengths::rgb(defaultChannelWavelengths());

const char* kChecker =
    "<texture name=\"radiance\" type=\"checkerboard\"><rgb name=\"color0\" value=\"4, 1, 0.5\"/>"
    "<rgb name=\"color1\" value=\"0.5, 2, 3\"/><transform name=\"to_uv\"><scale x=\"3\" y=\"2\"/></transform></texture>";

TEST(TexturedAreaLight, SamplesAndHitsSeeTheTextureAtTheirUv) {
    for (const std::string shape : {"rectangle", "sphere", "cylinder"}) {
        const std::string xml = "<scene version=\"3.0.0\"><shape type=\"" + shape + "\"><emitter type=\"area\">" + kChecker +
                                "</emitter><boolean name=\"flip_normals\" value=\"false\"/></shape></scene>";
        Scene scene(loadSceneFromString(xml, "."));
        ASSERT_EQ(scene.lights().size(), 1u) << shape;
        const Light& light = *scene.lights()[0];
        Pcg32 rng(9, 1);
        int checked = 0, seenBoth[2] = {0, 0};
        for (int i = 0; i < 400; ++i) {
            // Above the rectangle and the sphere; beside the cylinder (axis z from 0 to 1).
            const vec3 jitter = vec3(rng.uniform() - 0.5f, rng.uniform() - 0.5f, rng.uniform() - 0.5f);
            const vec3 p = shape == "cylinder" ? vec3(5.0f, 0.0f, 0.5f) + jitter * vec3(0.0f, 2.0f, 1.0f)
                                               : vec3(0.1f, 0.2f, 5.0f) + jitter * vec3(2.0f, 2.0f, 0.0f);
            const auto ls = light.sampleLi(p, vec2(rng.uniform(), rng.uniform()), kRGB);
            if (!ls) continue;
            // The ray towards the sample hits the light there; Le at the hit's uv equals the sample's L.
            const auto hit = scene.intersect(Ray(p, ls->wi));
            ASSERT_TRUE(hit.has_value()) << shape;
            if (glm::length(hit->p - ls->pLight) > 1e-3f) continue;  // another part of the shape in front
            EXPECT_NEAR(glm::length(hit->uv - ls->uv), 0.0f, 2e-4f) << shape;
            const SampledSpectrum le = hit->areaLight->Le(textureQueryAt(*hit), hit->ng, hit->wo, kRGB);
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(le[c], ls->L[c], 1e-5f * (1 + le[c])) << shape;
            ++seenBoth[le[0] > 1.0f ? 0 : 1];
            ++checked;
        }
        EXPECT_GT(checked, 100) << shape;
        EXPECT_GT(seenBoth[0], 10) << shape;  // both checker colours were sampled
        EXPECT_GT(seenBoth[1], 10) << shape;
    }
}

/// The mean Y of a 4 × 4 image of the floor point (1.2, 0.4, 0) lit by `emitters` (direct
/// lighting through next-event estimation and BSDF sampling).
double floorY(const std::string& emitters, double* stderrOut) {
    const std::string xml = R"(<scene version="3.0.0">
  <integrator type="direct"/>
  <sensor type="perspective"><float name="fov" value="0.5"/>
    <transform name="to_world"><lookat origin="1.2, 0.4, 0.5" target="1.2, 0.4, 0" up="0, 1, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="4"/><integer name="height" value="4"/></film>
  </sensor>
  <shape type="rectangle"><transform name="to_world"><scale value="100"/></transform><bsdf type="diffuse"/></shape>
)" + emitters + "</scene>";
    const test::ImageMean m = test::imageMean(test::renderXml(xml, 4, 4, 8192, 3, true), 1);
    *stderrOut = m.stderr_;
    return m.mean;
}

std::string quad(float x, float y, const char* rgb) {
    return "<shape type=\"rectangle\"><boolean name=\"flip_normals\" value=\"true\"/><transform name=\"to_world\">"
           "<scale value=\"0.5\"/><translate x=\"" + std::to_string(x) + "\" y=\"" + std::to_string(y) +
           "\" z=\"1.5\"/></transform><emitter type=\"area\"><rgb name=\"radiance\" value=\"" + rgb + "\"/></emitter></shape>\n";
}

TEST(TexturedAreaLight, ACheckerboardEmitterLightsAsItsConstantQuadsDo) {
    // The rectangle [−1, 1]² at z = 1.5 facing down, uv = ((x + 1)/2, (y + 1)/2): Mitsuba 3's
    // checkerboard is color0 where frac(u), frac(v) are both ≤ ½ or both > ½, i.e. on the quadrants
    // x < 0, y < 0 and x > 0, y > 0.
    const auto checker = [](const char* c0, const char* c1) {
        return std::string("<shape type=\"rectangle\"><boolean name=\"flip_normals\" value=\"true\"/>"
                           "<transform name=\"to_world\"><translate z=\"1.5\"/></transform><emitter type=\"area\">"
                           "<texture name=\"radiance\" type=\"checkerboard\"><rgb name=\"color0\" value=\"") +
               c0 + "\"/><rgb name=\"color1\" value=\"" + c1 + "\"/></texture></emitter></shape>\n";
    };
    const char *a = "3, 3, 3", *b = "0.5, 0.5, 0.5";
    double seT, seQ, seS;
    const double textured = floorY(checker(a, b), &seT);
    const double quads = floorY(quad(-0.5f, -0.5f, a) + quad(0.5f, 0.5f, a) + quad(0.5f, -0.5f, b) + quad(-0.5f, 0.5f, b), &seQ);
    EXPECT_GT(textured, 0.05);
    EXPECT_NEAR(textured, quads, 5 * std::sqrt(seT * seT + seQ * seQ));
    // The test can fail: the colours swapped light the (off-centre) floor point differently.
    const double swapped = floorY(checker(b, a), &seS);
    EXPECT_GT(std::abs(swapped - quads), 5 * std::sqrt(seS * seS + seQ * seQ));
}

}  // namespace
}  // namespace iris
