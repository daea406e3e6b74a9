// The `spot` emitter (render/lights/point_light.cpp) as Mitsuba 0.6 and 3 define it: full
// intensity within beam_width, none beyond cutoff_angle, a falloff linear in the angle in between
// (not pbrt's smoothstep, which a midway value tells apart); the projected `texture` looked up at
// Mitsuba 3's uv = ½ + ½ (x, y)/(z tan cutoff) of the direction in the light's frame; and the
// errors of a wrong spot.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "render/lights/light.h"
#include "render/loader/scene_loader.h"
#include "spectral/wavelengths.h"
#include "tests/support/error_of.h"
#include "tests/support/one_emitter.h"

namespace iris {
namespace {

const SampledWavelengths kRGB = SampledWavelengths::rgb(defaultChannelWavelengths());

/// The radiance the spot sends to the point at angle θ (radians) from its axis, distance 2, in the
/// x–z plane rotated by φ about the axis; times d² it is the intensity in that direction.
float intensityAt(const Light& l, float theta, float phi = 0.0f, int channel = 1) {
    const vec3 p = 2.0f * vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
    const auto s = l.sampleLi(p, vec2(0.5f), kRGB);
    return s ? s->L[channel] * 4.0f : 0.0f;
}

TEST(SpotLight, FalloffIsLinearInTheAngleAsMitsubas) {
    // cutoff 30°, beam 10°: 1 within 10°, 0 beyond 30°, (30° − θ)/20° between.
    const LightPtr spot = test::loadOneEmitter("spot", "<float name=\"intensity\" value=\"3\"/><float name=\"cutoff_angle\" value=\"30\"/>"
                                   "<float name=\"beam_width\" value=\"10\"/>");
    const float deg = kPi / 180.0f;
    EXPECT_NEAR(intensityAt(*spot, 0.0f), 3.0f, 1e-5f);
    EXPECT_NEAR(intensityAt(*spot, 9.0f * deg), 3.0f, 1e-5f);
    EXPECT_EQ(intensityAt(*spot, 31.0f * deg), 0.0f);
    EXPECT_EQ(intensityAt(*spot, kPi / 2), 0.0f);
    for (const float t : {12.0f, 20.0f, 25.0f, 29.0f})
        EXPECT_NEAR(intensityAt(*spot, t * deg, 1.3f), 3.0f * (30.0f - t) / 20.0f, 2e-4f) << t;
    // pbrt's smoothstep in cos θ would give 0.5036 × 3 midway at 20°, the linear ramp 0.5 × 3; and
    // Mitsuba's default beam_width is ¾ of the cutoff.
    EXPECT_GT(std::abs(intensityAt(*spot, 20.0f * deg) - 3.0f * 0.5036f), 5e-3f);
    const LightPtr def = test::loadOneEmitter("spot", "<float name=\"cutoff_angle\" value=\"40\"/>");
    EXPECT_NEAR(intensityAt(*def, 29.0f * deg), 1.0f, 1e-5f);
    EXPECT_NEAR(intensityAt(*def, 35.0f * deg), 0.5f, 2e-4f);
}

TEST(SpotLight, TextureIsProjectedAlongTheAxis) {
    // A 2 × 2 checkerboard over uv: with cutoff 45° (tan = 1) the direction (x, y, z) looks up
    // uv = ½ + ½ (x/z, y/z). Mitsuba 3's spectrum checkerboard: color0 where frac(u) and frac(v)
    // are both ≤ ½ or both > ½.
    const LightPtr spot = test::loadOneEmitter("spot",
        "<float name=\"cutoff_angle\" value=\"45\"/><float name=\"beam_width\" value=\"45\"/>"
        "<texture name=\"texture\" type=\"checkerboard\"><rgb name=\"color0\" value=\"0.8\"/><rgb name=\"color1\" value=\"0.2\"/></texture>");
    auto at = [&](float x, float y) {  // the point in direction (x, y, 1), distance |(x, y, 1)|
        const vec3 p(x, y, 1.0f);
        const auto s = spot->sampleLi(p, vec2(0.5f), kRGB);
        return s ? s->L[0] * glm::dot(p, p) : 0.0f;
    };
    EXPECT_NEAR(at(-0.5f, -0.5f), 0.8f, 1e-5f);  // uv (0.25, 0.25): both ≤ ½
    EXPECT_NEAR(at(0.5f, 0.5f), 0.8f, 1e-5f);    // uv (0.75, 0.75): both > ½
    EXPECT_NEAR(at(0.5f, -0.5f), 0.2f, 1e-5f);   // uv (0.75, 0.25)
    EXPECT_NEAR(at(-0.5f, 0.5f), 0.2f, 1e-5f);   // uv (0.25, 0.75)
    // The light's frame follows to_world: rotated 90° about its axis, (x, y) → (−y, x).
    const LightPtr turned = test::loadOneEmitter("spot",
        "<float name=\"cutoff_angle\" value=\"45\"/><float name=\"beam_width\" value=\"45\"/>"
        "<texture name=\"texture\" type=\"checkerboard\"><rgb name=\"color0\" value=\"0.8\"/><rgb name=\"color1\" value=\"0.2\"/></texture>"
        "<transform name=\"to_world\"><rotate z=\"1\" angle=\"90\"/></transform>");
    const vec3 p(0.5f, -0.5f, 1.0f);  // local (−0.5, −0.5): color0
    const auto s = turned->sampleLi(p, vec2(0.5f), kRGB);
    ASSERT_TRUE(s.has_value());
    EXPECT_NEAR(s->L[0] * glm::dot(p, p), 0.8f, 1e-5f);
}

TEST(SpotLight, WrongSpotsAreRefusedWithTheirLine) {
    const auto err = [](const std::string& body) { return test::sceneError("<emitter type=\"spot\">\n" + body + "</emitter>"); };
    const auto has = test::contains;
    const std::string constant = err("<rgb name=\"texture\" value=\"0.5\"/>\n");
    EXPECT_TRUE(has(constant, "<string>:3: spot: 'texture' must be spatially varying")) << constant;
    const std::string wide = err("<float name=\"cutoff_angle\" value=\"100\"/>\n<texture name=\"texture\" type=\"checkerboard\"/>\n");
    EXPECT_TRUE(has(wide, "<string>:3: spot: a projected texture needs cutoff_angle < 90")) << wide;
    const std::string beam = err("<float name=\"cutoff_angle\" value=\"20\"/>\n<float name=\"beam_width\" value=\"25\"/>\n");
    EXPECT_TRUE(has(beam, "<string>:4: spot beam_width must be in (0, cutoff_angle]")) << beam;
    EXPECT_EQ(err("<float name=\"cutoff_angle\" value=\"100\"/>\n"), "");  // wider than a hemisphere, no texture
}

}  // namespace
}  // namespace iris
