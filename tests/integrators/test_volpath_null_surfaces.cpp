// Pass-through surfaces in the volumetric integrators (integrators/volpath.cpp), against closed
// forms and Mitsuba 3's rules (src/integrators/volpath.cpp): a sampled pass-through lobe (the
// transmission of `thindielectric`, the transparent part of `mask`, `null`) is no bounce, and shadow
// rays cross such surfaces with the BSDF's null-transmission weight (eval_null_transmission:
// thindielectric 1 − R', mask 1 − opacity). Before these rules, a thindielectric boundary counted
// against max_depth and blocked next-event estimation, which made Mitsuba 3's media test scenes
// 12–17 % dark (issue 33). Fixed seeds; tolerances are 5 standard errors of the image mean.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "tests/support/image_mean.h"
#include "tests/support/polygon_irradiance.h"

using namespace iris;

namespace {

constexpr int kRes = 8;
const char* kIntegrators[] = {"volpath", "volpathmis"};

/// R' = R + T²R/(1 − R²) = 2R/(1 + R) of a slab of index eta at normal incidence.
double slabReflectance(double eta) {
    const double r = (eta - 1) * (eta - 1) / ((eta + 1) * (eta + 1));
    return 2 * r / (1 + r);
}

/// A camera at height camZ (default 5) looking straight down at the origin (fov 0.5°), integrator
/// `integ` with `maxDepth`, and `body`.
std::string scene(const std::string& integ, int maxDepth, const std::string& body, float camZ = 5.0f) {
    char head[1200];
    std::snprintf(head, sizeof head, R"(<scene version="3.0.0">
  <integrator type="%s"><integer name="max_depth" value="%d"/></integrator>
  <sensor type="perspective"><float name="fov" value="0.5"/>
    <transform name="to_world"><lookat origin="0 0 %g" target="0 0 0" up="0 1 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="%d"/><integer name="height" value="%d"/>
      <rfilter type="box"/></film></sensor>
)",
                  integ.c_str(), maxDepth, camZ, kRes, kRes);
    return head + body + "</scene>";
}

/// A horizontal 4×4 sheet at height z with the bsdf `bsdf`.
std::string sheet(float z, const std::string& bsdf) {
    char buf[600];
    std::snprintf(buf, sizeof buf, R"(<shape type="rectangle"><transform name="to_world"><scale value="2"/><translate z="%g"/></transform>
  %s</shape>
)",
                  z, bsdf.c_str());
    return buf;
}

const std::string kThinGlass = R"(<bsdf type="thindielectric"><float name="int_ior" value="1.5"/><float name="ext_ior" value="1"/></bsdf>)";
/// An opacity mask of 0.25 over a black diffuse surface: only the transparent part carries light.
const std::string kMask = R"(<bsdf type="mask"><float name="opacity" value="0.25"/>
  <bsdf type="diffuse"><float name="reflectance" value="0"/></bsdf></bsdf>)";

/// A diffuse floor (ρ = 0.5) at z = 0 lit by a point light of intensity 4 at z = 2: seen from
/// above, the floor's radiance is ρ/π · I/2² = 0.5/π (RGB mode).
const std::string kLitFloor = R"(<emitter type="point"><point name="position" value="0 0 2"/><float name="intensity" value="4"/></emitter>
<shape type="rectangle"><transform name="to_world"><scale value="10"/></transform>
  <bsdf type="diffuse"><float name="reflectance" value="0.5"/></bsdf></shape>
)";

/// An emitting floor of radiance 2 facing up.
const std::string kEmittingFloor = R"(<shape type="rectangle"><transform name="to_world"><scale value="10"/></transform>
  <emitter type="area"><rgb name="radiance" value="2, 2, 2"/></emitter></shape>
)";

Film render(const std::string& xml, bool rgb, int spp, uint64_t seed) { return test::renderXml(xml, kRes, kRes, spp, seed, rgb); }

}  // namespace

TEST(VolPathNullSurfaces, ThinDielectricTransmissionIsNoBounce) {
    // max_depth 1 renders directly visible emitters only (Mitsuba's convention). An emitter behind
    // a thin dielectric sheet is still directly visible: the camera sees (1 − R')·Le.
    const double expected = (1 - slabReflectance(1.5)) * 2.0;
    for (const char* integ : kIntegrators) {
        const Film f = render(scene(integ, 1, sheet(1.0f, kThinGlass) + kEmittingFloor), true, 256, 3);
        const test::ImageMean m = test::imageMean(f, 1);
        EXPECT_NEAR(m.mean, expected, 5 * m.stderr_ + 1e-4) << integ;
    }
}

TEST(VolPathNullSurfaces, ShadowRaysCrossAThinDielectricWithOneMinusSlabReflectance) {
    // Direct illumination (max_depth 2) of the floor through the sheet: the camera ray and the
    // shadow ray each cross it at normal incidence, (1 − R')² · ρ/π · I/d². Before the sheet
    // transmitted shadow rays the floor was black.
    const double t = 1 - slabReflectance(1.5);
    const double expected = t * t * 0.5 / M_PI;
    for (const char* integ : kIntegrators) {
        const Film f = render(scene(integ, 2, sheet(1.0f, kThinGlass) + kLitFloor), true, 512, 5);
        const test::ImageMean m = test::imageMean(f, 1);
        EXPECT_NEAR(m.mean, expected, 5 * m.stderr_ + 1e-4) << integ;
    }
}

TEST(VolPathNullSurfaces, ShadowRaysCrossAMaskWithOneMinusOpacity) {
    // The same through a mask of opacity 0.25: (1 − 0.25)² · ρ/π · I/d² (Mitsuba 3 mask.cpp,
    // eval_null_transmission = 1 − opacity · (1 − nested) with an opaque nested BSDF).
    const double expected = 0.75 * 0.75 * 0.5 / M_PI;
    for (const char* integ : kIntegrators) {
        const Film f = render(scene(integ, 2, sheet(1.0f, kMask) + kLitFloor), true, 512, 7);
        const test::ImageMean m = test::imageMean(f, 1);
        EXPECT_NEAR(m.mean, expected, 5 * m.stderr_ + 1e-4) << integ;
    }
}

TEST(VolPathNullSurfaces, AnOpaqueSheetStillBlocksShadowRays) {
    // The same closed-form test fails for a sheet that must block (a smooth dielectric refracts:
    // it has no pass-through lobe), so the tests above can tell crossing from blocking.
    const std::string glass = R"(<bsdf type="dielectric"><float name="int_ior" value="1.5"/></bsdf>)";
    const Film f = render(scene("volpath", 2, sheet(1.0f, glass) + kLitFloor), true, 256, 9);
    EXPECT_EQ(test::imageMean(f, 1).mean, 0.0);
}

TEST(VolPathNullSurfaces, SpectralModeMatchesTheUncoveredFloorTimesTheCrossings) {
    // Spectral mode: the covered floor equals the uncovered floor times (1 − R')², the index
    // being constant over wavelength.
    const double t = 1 - slabReflectance(1.5);
    const Film open = render(scene("volpath", 2, kLitFloor), false, 64, 11);
    for (const char* integ : kIntegrators) {
        const Film covered = render(scene(integ, 2, sheet(1.0f, kThinGlass) + kLitFloor), false, 512, 13);
        for (int c = 0; c < 3; ++c) {
            const test::ImageMean a = test::imageMean(covered, c), b = test::imageMean(open, c);
            EXPECT_NEAR(a.mean, t * t * b.mean, 5 * std::hypot(a.stderr_, t * t * b.stderr_) + 1e-4) << integ << " channel " << c;
        }
    }
}

TEST(VolPathNullSurfaces, PathStillCountsTheSheetAndBlocksShadowRays) {
    // Mitsuba 3's `path` counts every intersection as a bounce and its shadow rays are occlusion
    // tests: behind the sheet the emitter needs max_depth 2, and the point-lit floor stays black.
    const Film seen = render(scene("path", 1, sheet(1.0f, kThinGlass) + kEmittingFloor), true, 64, 15);
    EXPECT_EQ(test::imageMean(seen, 1).mean, 0.0);
    const Film lit = render(scene("path", 2, sheet(1.0f, kThinGlass) + kLitFloor), true, 64, 17);
    EXPECT_EQ(test::imageMean(lit, 1).mean, 0.0);
}

TEST(VolPathNullSurfaces, AreaLightSeenThroughANullSheetKeepsMISConsistent) {
    // A floor (ρ = 0.8) lit by a square light (half-size 1, radiance 3, height 2) through a `null`
    // sheet at height 1: next-event estimation and BSDF sampling meet at the light, the latter
    // after crossing the sheet. Direct illumination must be Lambert's polygon irradiance ρ/π · E;
    // it was ~3 % high while the light's pdf was taken from the crossing instead of the floor.
    const std::string light = R"(<shape type="rectangle"><boolean name="flip_normals" value="true"/>
  <transform name="to_world"><translate z="2"/></transform>
  <emitter type="area"><rgb name="radiance" value="3, 3, 3"/></emitter></shape>
<shape type="rectangle"><transform name="to_world"><scale value="100"/></transform>
  <bsdf type="diffuse"><float name="reflectance" value="0.8"/></bsdf></shape>
)";
    const double expected = 0.8 / M_PI * test::squareLightIrradiance(1.0f, 2.0f, 3.0f);
    for (const char* integ : kIntegrators) {
        // The camera below the sheet (the light would hide the floor from above).
        const Film f = render(scene(integ, 2, sheet(1.0f, R"(<bsdf type="null"/>)") + light, 0.5f), true, 4096, 25);
        const test::ImageMean m = test::imageMean(f, 1);
        EXPECT_NEAR(m.mean, expected, 5 * m.stderr_ + 1e-4) << integ;
    }
}
