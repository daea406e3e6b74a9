// The volumetric integrators (integrators/volpath.cpp) against closed forms: Beer–Lambert
// transmittance through an absorbing medium, the furnace (a non-absorbing medium inside a uniform
// environment keeps radiance 1, whatever σ_t, its wavelength dependence or the phase function),
// a sensor inside a medium, an emitter inside a medium; volpath and volpathmis agree with each
// other and volpathmis is less noisy on a chromatic medium; bad media input is refused with
// file:line. Fixed seeds; tolerances are 5 standard errors of the image mean estimated from the
// spread of the (independent, identically distributed) pixel means.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"
#include "tests/support/image_mean.h"

using namespace iris;

namespace {

constexpr int kRes = 8;

/// A camera at z = dist looking at the origin over an 8×8 film with `fov` degrees, the integrator
/// `integrator` (max_depth −1), an optional sensor medium reference, and `body`.
std::string scene(const std::string& integrator, const std::string& body, float fov = 0.5f, float dist = 4.0f,
                  const std::string& sensorMedium = "") {
    char head[1400];
    std::snprintf(head, sizeof head, R"(<scene version="3.0.0">
  <integrator type="%s"/>
  <sensor type="perspective"><float name="fov" value="%g"/>%s
    <transform name="to_world"><lookat origin="0 0 %g" target="0 0 0" up="0 1 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="%d"/><integer name="height" value="%d"/>
      <rfilter type="box"/></film></sensor>
)",
                  integrator.c_str(), fov, sensorMedium.c_str(), dist, kRes, kRes);
    return head + body + "</scene>";
}

const std::string kConstant = R"(<emitter type="constant"><float name="radiance" value="1"/></emitter>)" "\n";

/// A sphere of radius r at the origin with a null boundary and the medium `id` inside.
std::string mediumSphere(const std::string& id, float r = 1.0f) {
    char buf[400];
    std::snprintf(buf, sizeof buf, R"(<shape type="sphere"><float name="radius" value="%g"/><bsdf type="null"/>
  <ref name="interior" id="%s"/></shape>
)", r, id.c_str());
    return buf;
}

struct Options {
    bool rgb = true;
    int spp = 64;
    uint64_t seed = 7;
};

Film render(const std::string& xml, const Options& o) { return test::renderXml(xml, kRes, kRes, o.spp, o.seed, o.rgb); }

using Mean = test::ImageMean;
using test::imageMean;

const char* kIntegrators[] = {"volpath", "volpathmis"};

}  // namespace

TEST(VolPath, BeerLambertThroughAnAbsorbingSphereInRGB) {
    // Rays within 0.5° of the axis cross 2·√(1 − b²) ≈ 2 (to 4e-4) of σ_t per channel: the pixel
    // is e^{−2σ} (Beer–Lambert) of the environment's 1.
    const std::string medium = R"(<medium type="homogeneous" id="m"><rgb name="sigma_t" value="0.2, 0.5, 1.0"/>
  <float name="albedo" value="0"/></medium>
)";
    for (const char* integ : kIntegrators) {
        const Film f = render(scene(integ, kConstant + medium + mediumSphere("m")), {true, 256});
        const float sigma[3] = {0.2f, 0.5f, 1.0f};
        for (int c = 0; c < 3; ++c) {
            const Mean m = imageMean(f, c);
            EXPECT_NEAR(m.mean, std::exp(-2.0 * sigma[c]), 5 * m.stderr_ + 1e-3) << integ << " channel " << c;
            EXPECT_LT(m.stderr_, 0.02) << integ;
        }
    }
}

TEST(VolPath, BeerLambertFailsForAWrongThickness) {
    // The same test must notice a medium of twice the extinction (proves the tolerance can fail).
    const std::string medium = R"(<medium type="homogeneous" id="m"><float name="sigma_t" value="1.0"/>
  <float name="albedo" value="0"/></medium>
)";
    const Film f = render(scene("volpath", kConstant + medium + mediumSphere("m")), {true, 256});
    const Mean m = imageMean(f, 1);
    EXPECT_GT(std::abs(m.mean - std::exp(-2.0 * 0.5)), 5 * m.stderr_ + 1e-3);
    EXPECT_NEAR(m.mean, std::exp(-2.0), 5 * m.stderr_ + 1e-3);
}

TEST(VolPath, FurnaceKeepsRadianceWithChromaticMediaInBothModes) {
    // σ_s = σ_t (albedo 1): a medium inside a uniform environment of radiance L_e has radiance
    // L_e everywhere, for any σ_t(λ) and phase function. In spectral mode σ_t varies by 10x over
    // the spectrum, which makes volpath's single-lane weights spread widely; both must average to
    // the environment (rendered alone for the spectral reference: D65 with Y = 1 in Rec.709).
    const std::pair<const char*, const char*> media[] = {
        {"iso", R"(<medium type="homogeneous" id="iso"><spectrum name="sigma_t" value="400:0.3, 550:1.5, 700:3.0"/>
  <float name="albedo" value="1"/></medium>)"},
        {"hg", R"(<medium type="homogeneous" id="hg"><spectrum name="sigma_t" value="400:3.0, 700:0.3"/><float name="albedo" value="1"/>
  <phase type="hg"><float name="g" value="0.7"/></phase></medium>)"},
        {"ray", R"(<medium type="homogeneous" id="ray"><float name="sigma_t" value="2"/><float name="albedo" value="1"/>
  <phase type="rayleigh"/></medium>)"},
    };
    for (const bool rgb : {true, false}) {
        const Film empty = render(scene("volpath", kConstant, 30.0f), {rgb, 64});
        for (const auto& [id, xml] : media) {
            const std::string one = std::string(xml) + "\n";
            for (const char* integ : kIntegrators) {
                const Film f = render(scene(integ, kConstant + one + mediumSphere(id), 30.0f), {rgb, 128});
                for (int c = 0; c < 3; ++c) {
                    const Mean m = imageMean(f, c), e = imageMean(empty, c);
                    EXPECT_NEAR(m.mean, e.mean, 5 * std::hypot(m.stderr_, e.stderr_) + 2e-3)
                        << integ << " " << id << (rgb ? " rgb" : " spectral") << " channel " << c;
                }
            }
        }
    }
}

TEST(VolPath, ALaneWithZeroAlbedoDoesNotEndTheOthers) {
    // Albedo (1, 0, 0) under a uniform environment: red is a furnace (radiance 1), green and blue a
    // pure absorber, e^{−2σ} along the axis. Absorption must be a per-lane weight, not an event
    // chosen in the sampling lane: choosing it in a lane of albedo 0 would end red's scattering
    // too (red then came out (1 + 2e^{−2})/3 ≈ 0.42).
    const std::string medium = R"(<medium type="homogeneous" id="m"><float name="sigma_t" value="1"/>
  <rgb name="albedo" value="1, 0, 0"/></medium>
)";
    for (const char* integ : kIntegrators) {
        const Film f = render(scene(integ, kConstant + medium + mediumSphere("m")), {true, 512, 19});
        const Mean red = imageMean(f, 0), green = imageMean(f, 1);
        EXPECT_NEAR(red.mean, 1.0, 5 * red.stderr_ + 2e-3) << integ;
        EXPECT_NEAR(green.mean, std::exp(-2.0), 5 * green.stderr_ + 1e-3) << integ;
    }
}

TEST(VolPath, SensorInsideAMedium) {
    // The camera at the centre of a null sphere of radius 1 filled with an absorbing medium: every
    // ray crosses 1 unit, e^{−σ}.
    const std::string body = kConstant + R"(<medium type="homogeneous" id="m"><float name="sigma_t" value="0.7"/>
  <float name="albedo" value="0"/></medium>
<shape type="sphere"><float name="radius" value="1"/><point name="center" value="0 0 4"/><bsdf type="null"/>
  <ref name="interior" id="m"/></shape>
)";
    for (const char* integ : kIntegrators) {
        const Film f = render(scene(integ, body, 30.0f, 4.0f, R"(<ref name="medium" id="m"/>)"), {true, 128});
        const Mean m = imageMean(f, 1);
        EXPECT_NEAR(m.mean, std::exp(-0.7), 5 * m.stderr_ + 1e-3) << integ;
    }
}

TEST(VolPath, EmitterInsideAMedium) {
    // An emitting sphere of radius 0.5 (radiance 2) at the centre of an absorbing sphere of radius
    // 2, seen along the axis: the camera sees 2·e^{−1.5σ} (no environment).
    const std::string body = R"(<medium type="homogeneous" id="m"><float name="sigma_t" value="0.4"/>
  <float name="albedo" value="0"/></medium>
<shape type="sphere"><float name="radius" value="0.5"/><emitter type="area"><rgb name="radiance" value="2, 2, 2"/></emitter></shape>
)" + mediumSphere("m", 2.0f);
    for (const char* integ : kIntegrators) {
        const Film f = render(scene(integ, body, 0.5f, 6.0f), {true, 128});
        const Mean m = imageMean(f, 1);
        EXPECT_NEAR(m.mean, 2.0 * std::exp(-1.5 * 0.4), 5 * m.stderr_ + 2e-3) << integ;
    }
}

namespace {

/// A chromatic scattering medium (σ_t from 0.2 to 4 over the spectrum) in a box over a white
/// floor under a small area light and a dim environment: single and multiple scattering,
/// next-event estimation through the null boundary, surfaces inside the medium.
std::string chromaticScene(const std::string& integ) {
    return scene(integ, R"(<emitter type="constant"><float name="radiance" value="0.2"/></emitter>
<medium type="homogeneous" id="m"><spectrum name="sigma_t" value="400:4.0, 550:1.0, 700:0.2"/>
  <float name="albedo" value="0.8"/><phase type="hg"><float name="g" value="0.3"/></phase></medium>
<shape type="cube"><bsdf type="null"/><ref name="interior" id="m"/></shape>
<shape type="rectangle"><transform name="to_world"><scale value="3"/><translate z="-1.2"/></transform>
  <bsdf type="diffuse"><float name="reflectance" value="0.8"/></bsdf></shape>
<shape type="sphere"><point name="center" value="0 3 3"/><float name="radius" value="0.3"/>
  <emitter type="area"><float name="radiance" value="20"/></emitter></shape>
)", 40.0f, 5.0f);
}

}  // namespace

TEST(VolPath, VolpathAndVolpathmisAgreeAndMISIsLessNoisyOnAChromaticMedium) {
    const Film a = render(chromaticScene("volpath"), {false, 256, 11});
    const Film b = render(chromaticScene("volpathmis"), {false, 256, 12});
    double noiseA = 0, noiseB = 0;
    const std::vector<float> varA = a.varianceOfMeanImage(), varB = b.varianceOfMeanImage();
    for (size_t i = 0; i < varA.size(); ++i) {
        noiseA += varA[i];
        noiseB += varB[i];
    }
    for (int c = 0; c < 3; ++c) {
        const Mean ma = imageMean(a, c), mb = imageMean(b, c);
        EXPECT_NEAR(ma.mean, mb.mean, 5 * std::hypot(ma.stderr_, mb.stderr_)) << "channel " << c;
        EXPECT_GT(ma.mean, 0.01);
    }
    EXPECT_LT(noiseB, noiseA) << "volpathmis variance " << noiseB << " vs volpath " << noiseA;
}

TEST(VolPath, RGBModeAgreesBetweenIntegrators) {
    const std::string medium = R"(<emitter type="constant"><float name="radiance" value="0.5"/></emitter>
<medium type="homogeneous" id="m"><rgb name="sigma_t" value="0.3, 1.0, 2.5"/><rgb name="albedo" value="0.9, 0.6, 0.3"/></medium>
<shape type="sphere"><bsdf type="null"/><ref name="interior" id="m"/></shape>
<shape type="sphere"><point name="center" value="2 2 2"/><float name="radius" value="0.5"/>
  <emitter type="area"><float name="radiance" value="10"/></emitter></shape>
)";
    const Film a = render(scene("volpath", medium, 30.0f), {true, 256, 3});
    const Film b = render(scene("volpathmis", medium, 30.0f), {true, 256, 4});
    for (int c = 0; c < 3; ++c) {
        const Mean ma = imageMean(a, c), mb = imageMean(b, c);
        EXPECT_NEAR(ma.mean, mb.mean, 5 * std::hypot(ma.stderr_, mb.stderr_)) << "channel " << c;
    }
}

TEST(VolPath, ScenesWithoutMediaRenderAsPath) {
    // Without media, volpath is a path tracer: its image matches `path` statistically.
    const std::string body = kConstant + R"(<shape type="sphere"><bsdf type="diffuse"><float name="reflectance" value="0.5"/></bsdf></shape>
)";
    const Film a = render(scene("path", body, 30.0f), {true, 256, 1});
    const Film b = render(scene("volpath", body, 30.0f), {true, 256, 2});
    const Mean ma = imageMean(a, 1), mb = imageMean(b, 1);
    EXPECT_NEAR(ma.mean, mb.mean, 5 * std::hypot(ma.stderr_, mb.stderr_));
}

namespace {

std::string errorOf(const std::string& xml) {
    try {
        loadSceneFromString(xml, ".");
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(VolPath, BadMediaInputIsRefusedWithItsLine) {
    const std::string good = R"(<medium type="homogeneous" id="m"><float name="sigma_t" value="1"/></medium>
)";
    // A medium nobody refers to has no boundary.
    std::string e = errorOf(scene("volpath", good));
    EXPECT_NE(e.find("<string>:7"), std::string::npos) << e;
    EXPECT_NE(e.find("has no boundary"), std::string::npos) << e;
    // An open surface cannot enclose a medium.
    e = errorOf(scene("volpath", good + R"(<shape type="rectangle"><ref name="interior" id="m"/></shape>)"));
    EXPECT_NE(e.find("not a closed surface"), std::string::npos) << e;
    // Negative extinction, albedo above 1, a bad asymmetry parameter.
    e = errorOf(scene("volpath", R"(<medium type="homogeneous" id="m">
<float name="sigma_t" value="-0.5"/></medium>)" + mediumSphere("m")));
    EXPECT_NE(e.find("<string>:8"), std::string::npos) << e;
    EXPECT_NE(e.find("sigma_t = -0.5"), std::string::npos) << e;
    e = errorOf(scene("volpath", R"(<medium type="homogeneous" id="m"><float name="albedo" value="1.5"/></medium>)" + mediumSphere("m")));
    EXPECT_NE(e.find("albedo = 1.5"), std::string::npos) << e;
    e = errorOf(scene("volpath", R"(<medium type="homogeneous" id="m"><phase type="hg"><float name="g" value="1"/></phase></medium>)" +
                                     mediumSphere("m")));
    EXPECT_NE(e.find("must lie in (-1, 1)"), std::string::npos) << e;
    // An integrator that ignores media.
    e = errorOf(scene("path", good + mediumSphere("m")));
    EXPECT_NE(e.find("use 'volpath' or 'volpathmis'"), std::string::npos) << e;
    // The same good scene loads with volpath.
    EXPECT_EQ(errorOf(scene("volpath", good + mediumSphere("m"))), "");
}
