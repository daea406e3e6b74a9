// Emitting media (Mitsuba 3's volumelight, media/volume_light.h) in the volumetric integrators,
// against closed forms of the radiative transfer equation with the source term j (radiance per
// unit length): through an absorbing emitting sphere along a chord of length d, L = j (1 − e^{−σ d})/σ;
// inside an infinite scattering medium, L = j / σ_a (balance of emission and absorption). The
// volumelight nested in the medium and attached to the shape are the same light. Fixed seeds;
// tolerances are 5 standard errors of the image mean.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "tests/support/error_of.h"
#include "tests/support/image_mean.h"

using namespace iris;

namespace {

constexpr int kRes = 8;

/// A camera at z = 4 looking at the origin with `fov` degrees, integrator `integ`, the sensor in
/// medium `sensorMedium` ("" for none), and `body`.
std::string scene(const std::string& integ, const std::string& body, float fov = 0.5f, const std::string& sensorMedium = "") {
    char head[1200];
    std::snprintf(head, sizeof head, R"(<scene version="3.0.0">
  <integrator type="%s"/>
  <sensor type="perspective"><float name="fov" value="%g"/>%s
    <transform name="to_world"><lookat origin="0 0 4" target="0 0 0" up="0 1 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="%d"/><integer name="height" value="%d"/><rfilter type="box"/></film></sensor>
)",
                  integ.c_str(), fov, sensorMedium.c_str(), kRes, kRes);
    return head + body + "</scene>";
}

/// An absorbing unit sphere of extinction sigma emitting j, the light nested in the medium or
/// attached to the shape.
std::string emittingSphere(float sigma, const std::string& j, bool attached) {
    char buf[900];
    const std::string light = "<emitter type=\"volumelight\">" + j + "</emitter>";
    std::snprintf(buf, sizeof buf, R"(<medium type="homogeneous" id="m"><float name="sigma_t" value="%g"/><float name="albedo" value="0"/>%s</medium>
<shape type="sphere"><bsdf type="null"/><ref name="interior" id="m"/>%s</shape>
)",
                  sigma, attached ? "" : light.c_str(), attached ? light.c_str() : "");
    return buf;
}

const char* kIntegrators[] = {"volpath", "volpathmis"};

}  // namespace

TEST(VolumeLight, AbsorbingEmittingSphereIsTheClosedForm) {
    // Rays within 0.5° of the axis cross 2 units: L = j (1 − e^{−2σ}) / σ per channel.
    const float sigma = 0.7f;
    const float j[3] = {0.5f, 1.0f, 2.0f};
    for (const bool attached : {false, true})
        for (const char* integ : kIntegrators) {
            const Film f = test::renderXml(scene(integ, emittingSphere(sigma, R"(<rgb name="radiance" value="0.5, 1, 2"/>)", attached)),
                                           kRes, kRes, 256, 5, true);
            for (int c = 0; c < 3; ++c) {
                const test::ImageMean m = test::imageMean(f, c);
                EXPECT_NEAR(m.mean, j[c] * (1 - std::exp(-2.0 * sigma)) / sigma, 5 * m.stderr_ + 2e-3)
                    << integ << (attached ? " attached" : " nested") << " channel " << c;
            }
        }
}

TEST(VolumeLight, SpectralModeScalesWithTheClosedForm) {
    // A flat spectrum: the ratio of two extinctions' images is the closed forms' ratio in every channel.
    auto closed = [](double s) { return (1 - std::exp(-2.0 * s)) / s; };
    const Film thin = test::renderXml(scene("volpath", emittingSphere(0.3f, R"(<float name="radiance" value="1"/>)", false)),
                                      kRes, kRes, 256, 7, false);
    const Film thick = test::renderXml(scene("volpath", emittingSphere(3.0f, R"(<float name="radiance" value="1"/>)", false)),
                                       kRes, kRes, 256, 9, false);
    for (int c = 0; c < 3; ++c) {
        const test::ImageMean a = test::imageMean(thin, c), b = test::imageMean(thick, c);
        const double ratio = a.mean / b.mean, err = ratio * std::hypot(a.stderr_ / a.mean, b.stderr_ / b.mean);
        EXPECT_NEAR(ratio, closed(0.3) / closed(3.0), 5 * err + 1e-3) << "channel " << c;
    }
}

TEST(VolumeLight, InfiniteScatteringMediumBalancesEmissionAndAbsorption) {
    // The camera inside an unbounded medium of σ_t = 1 and albedo 0.8: L = j / σ_a = j / 0.2.
    // Multiple scattering carries 80 % of it, so a depth limit or a lost scattering order fails this.
    const std::string medium = R"(<medium type="homogeneous" id="m"><float name="sigma_t" value="1"/><float name="albedo" value="0.8"/>
  <emitter type="volumelight"><float name="radiance" value="0.3"/></emitter></medium>
)";
    for (const char* integ : kIntegrators) {
        const Film f = test::renderXml(scene(integ, medium, 30.0f, R"(<ref name="medium" id="m"/>)"), kRes, kRes, 256, 11, true);
        const test::ImageMean m = test::imageMean(f, 1);
        EXPECT_NEAR(m.mean, 0.3 / 0.2, 5 * m.stderr_ + 5e-3) << integ;
    }
}

TEST(VolumeLight, ErrorsNameTheirLine) {
    // to_world is the shape's; a volumelight needs a medium to emit; one emitter per medium; a
    // top-level volumelight says where it belongs.
    std::string e = test::sceneError(emittingSphere(1.0f, R"(<transform name="to_world"><translate x="1"/></transform>)", false));
    EXPECT_NE(e.find("'to_world' transformation is not allowed"), std::string::npos) << e;
    EXPECT_NE(e.find("<string>:2"), std::string::npos) << e;  // the medium line holding the transform
    e = test::sceneError(R"(<shape type="sphere"><emitter type="volumelight"><float name="radiance" value="1"/></emitter></shape>)");
    EXPECT_NE(e.find("needs a shape with an interior medium"), std::string::npos) << e;
    e = test::sceneError(R"(<medium type="homogeneous" id="m"><emitter type="volumelight"/></medium>
<shape type="sphere"><ref name="interior" id="m"/><emitter type="volumelight"/></shape>)");
    EXPECT_NE(e.find("has an emitter already"), std::string::npos) << e;
    e = test::sceneError(R"(<emitter type="volumelight"/>)");
    EXPECT_NE(e.find("belongs to a medium"), std::string::npos) << e;
    e = test::sceneError(emittingSphere(1.0f, R"(<float name="radiance" value="-1"/>)", true));
    EXPECT_NE(e.find("negative"), std::string::npos) << e;
}
