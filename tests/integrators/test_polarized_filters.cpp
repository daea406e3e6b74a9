// Polarized mode end to end (docs/polarization.md): ideal filters between an area light and the
// camera, rendered with the `stokes` integrator, against Mueller calculus — Malus's law, crossed
// polarizers, and Mitsuba 3's own path-tracer test of a quarter-wave plate (test_retarder.py
// test06: a polarizer at ±45° then a quarter-wave plate; the camera measures left / right circular
// light). Every path here is deterministic (delta lobes only), so the values are exact up to
// float rounding.
#include <gtest/gtest.h>

#include "render/film.h"
#include "render/loader/scene_loader.h"
#include "render/renderer.h"
#include "render/scene.h"
#include "render/stokes_film.h"

using namespace iris;

namespace {

/// The camera at (0, 10, 0) looks at the origin (up +z); the light at y = −10 faces it; `filters`
/// are rectangles between them, facing the camera (Mitsuba 3 test_retarder.py test06).
std::string filterScene(const std::string& filters, const std::string& integrator = "stokes") {
    return R"(<scene version="2.0.0">
  <integrator type=")" + integrator + R"("><integrator type="path"/></integrator>
  <sensor type="perspective"><float name="fov" value="0.5"/>
    <transform name="to_world"><lookat origin="0, 10, 0" target="0, 0, 0" up="0, 0, 1"/></transform>
    <film type="hdrfilm"><integer name="width" value="1"/><integer name="height" value="1"/><rfilter type="box"/></film></sensor>
  <shape type="rectangle">
    <transform name="to_world"><rotate x="1" angle="-90"/><translate y="-10"/></transform>
    <emitter type="area"><spectrum name="radiance" value="1"/></emitter></shape>
  )" + filters + "\n</scene>";
}

/// A filter rectangle at height y, rotated by `angle` degrees about the optical axis.
std::string filter(const std::string& bsdf, float y, float angle = 0.0f) {
    return "<shape type=\"rectangle\">" + bsdf + "<transform name=\"to_world\"><rotate x=\"1\" angle=\"-90\"/><rotate y=\"1\" angle=\"" +
           std::to_string(angle) + "\"/><translate y=\"" + std::to_string(y) + "\"/></transform></shape>";
}
const std::string kPolarizer = R"(<bsdf type="polarizer"/>)";
const std::string kQuarterWave = R"(<bsdf type="retarder"><spectrum name="delta" value="90"/></bsdf>)";

/// S0..S3 (CIE Y of each) measured through the pixel, in the stokes integrator's camera basis,
/// relative to the light seen without filters (the same seed: the same wavelengths, so the ratio
/// has no spectral sampling noise).
std::array<double, 4> measureStokes(const std::string& xml);

std::array<double, 4> measureStokesAbsolute(const std::string& xml) {
    const Scene scene(loadSceneFromString(xml, "."));
    RenderOptions opt;
    opt.spp = 4;
    opt.polarized = true;
    Film film(1, 1);
    StokesFilm stokes(1, 1);
    Renderer(scene, opt).render(film, nullptr, nullptr, &stokes);
    std::array<double, 4> s{};
    for (int k = 0; k < 4; ++k) s[size_t(k)] = stokes.component(k).pixel(0, 0).y;
    EXPECT_NEAR(s[0], film.pixel(0, 0).y, 1e-6 * (1 + s[0]));  // the image is S0
    return s;
}

std::array<double, 4> measureStokes(const std::string& xml) {
    static const double unfiltered = measureStokesAbsolute(filterScene(""))[0];
    std::array<double, 4> s = measureStokesAbsolute(xml);
    for (double& c : s) c /= unfiltered;
    return s;
}

}  // namespace

TEST(PolarizedFilters, QuarterWavePlateAfterA45DegreePolarizerGivesCircularLight) {
    // Mitsuba 3 test_retarder.py test06: +45° → left circular (1, 0, 0, −1), −45° → right
    // circular (1, 0, 0, +1), in the basis x = (−1, 0, 0) the stokes integrator uses here.
    for (float angle : {45.0f, -45.0f}) {
        const auto s = measureStokes(filterScene(filter(kPolarizer, -5, angle) + filter(kQuarterWave, 0)));
        ASSERT_GT(s[0], 0.1);
        EXPECT_NEAR(s[1] / s[0], 0.0, 1e-3) << angle;
        EXPECT_NEAR(s[2] / s[0], 0.0, 1e-3) << angle;
        EXPECT_NEAR(s[3] / s[0], angle > 0 ? -1.0 : 1.0, 1e-3) << angle;
        EXPECT_NEAR(s[0], 0.5, 1e-3);  // half of the unit radiance passes the polarizer
    }
}

TEST(PolarizedFilters, MalusLawThroughTwoPolarizers) {
    // I(θ) = ½ cos²θ for polarizers at 0 and θ (Malus 1809); the light leaving is linear along
    // the second polarizer: S1 = I cos 2θ', S2 = I sin 2θ' for its axis angle θ' in the camera
    // basis (the sign of S2 checks the sense of every basis rotation on the path).
    const auto s0 = measureStokes(filterScene(filter(kPolarizer, -5, 0) + filter(kPolarizer, 0, 0)));
    for (float angle : {0.0f, 30.0f, 45.0f, 60.0f, 90.0f, 120.0f}) {
        const auto s = measureStokes(filterScene(filter(kPolarizer, -5, 0) + filter(kPolarizer, 0, angle)));
        const double t = angle * kPi / 180;
        EXPECT_NEAR(s[0], 0.5 * std::cos(t) * std::cos(t), 2e-4) << angle;
        if (s[0] < 1e-3) continue;
        const double dop = std::sqrt(s[1] * s[1] + s[2] * s[2] + s[3] * s[3]) / s[0];
        EXPECT_NEAR(dop, 1.0, 1e-3) << angle;
        // Relative to the first configuration's axis (θ = 0), the axis turned by +θ: S2 > 0 for a
        // polarizer turned by +45° about the beam, the state the quarter-wave test above turns
        // into Mitsuba's left circular light.
        const double phi0 = 0.5 * std::atan2(s0[2], s0[1]), phi = 0.5 * std::atan2(s[2], s[1]);
        EXPECT_NEAR(std::remainder(phi - phi0 - t, kPi), 0.0, 1e-3) << angle;
    }
}

TEST(PolarizedFilters, CrossedPolarizersTransmitNothingAndAThirdOneOpensThem) {
    const auto crossed = measureStokes(filterScene(filter(kPolarizer, -6, 0) + filter(kPolarizer, 0, 90)));
    EXPECT_NEAR(crossed[0], 0.0, 1e-6);
    const auto opened = measureStokes(filterScene(filter(kPolarizer, -6, 0) + filter(kPolarizer, -3, 45) + filter(kPolarizer, 0, 90)));
    EXPECT_NEAR(opened[0], 0.125, 1e-4);
}

TEST(PolarizedFilters, TheStokesIntegratorNeedsPolarizedMode) {
    const Scene scene(loadSceneFromString(filterScene(filter(kPolarizer, 0)), "."));
    RenderOptions opt;
    opt.spp = 1;
    EXPECT_THROW(Renderer(scene, opt), Error);
}
