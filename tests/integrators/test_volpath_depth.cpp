// max_depth in the volumetric integrators (Mitsuba 3 src/integrators/volpath.cpp): max_depth − 1
// scattering vertices, each with next-event estimation, whether it is a surface bounce or a
// scattering event in a medium. The oracle is single scattering of a point light in an infinite
// homogeneous medium, L = ∫ σ_s p(θ) I / r(t)² e^{−σ_t (t + r(t))} dt along the camera ray
// (radiative transfer, e.g. pbrt-v4 §11.1 eq. 11.10 with one scattering event), integrated here by
// Simpson's rule. Fixed seeds; tolerance 5 standard errors of the image mean.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "tests/support/image_mean.h"

using namespace iris;

namespace {

constexpr int kRes = 8;
constexpr double kSigmaT = 0.5, kAlbedo = 0.8, kIntensity = 10.0, kLightOffset = 1.0, kCameraZ = 5.0;

/// A camera at z = 5 looking down −z (fov 0.5°) inside an infinite homogeneous medium with an
/// isotropic phase function, and a point light at (0, 1, 0).
std::string scene(const std::string& integ, int maxDepth) {
    char xml[1800];
    std::snprintf(xml, sizeof xml, R"(<scene version="3.0.0">
  <integrator type="%s"><integer name="max_depth" value="%d"/></integrator>
  <medium type="homogeneous" id="m"><float name="sigma_t" value="%g"/><float name="albedo" value="%g"/></medium>
  <sensor type="perspective"><float name="fov" value="0.5"/><ref name="medium" id="m"/>
    <transform name="to_world"><lookat origin="0 0 %g" target="0 0 0" up="0 1 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="%d"/><integer name="height" value="%d"/>
      <rfilter type="box"/></film></sensor>
  <emitter type="point"><point name="position" value="0 %g 0"/><float name="intensity" value="%g"/></emitter>
</scene>)",
                  integ.c_str(), maxDepth, kSigmaT, kAlbedo, kCameraZ, kRes, kRes, kLightOffset, kIntensity);
    return xml;
}

/// Single-scattered radiance along the axis ray: Simpson's rule over t in [0, 80] (e^{−40} beyond).
double singleScattering() {
    const int n = 20000;
    const double a = 0, b = 80, h = (b - a) / n;
    auto f = [](double t) {
        const double z = kCameraZ - t, r2 = kLightOffset * kLightOffset + z * z, r = std::sqrt(r2);
        return kAlbedo * kSigmaT / (4 * M_PI) * kIntensity / r2 * std::exp(-kSigmaT * (t + r));
    };
    double s = f(a) + f(b);
    for (int i = 1; i < n; ++i) s += (i % 2 ? 4 : 2) * f(a + i * h);
    return s * h / 3;
}

}  // namespace

TEST(VolPathDepth, MaxDepthTwoIsSingleScatteringInAMedium) {
    // max_depth 2 allows one scattering vertex with next-event estimation (a point light cannot be
    // hit, so every contribution is next-event estimation at the first scattering event).
    const double expected = singleScattering();
    for (const char* integ : {"volpath", "volpathmis"}) {
        const Film f = test::renderXml(scene(integ, 2), kRes, kRes, 1024, 21, true);
        const test::ImageMean m = test::imageMean(f, 1);
        EXPECT_NEAR(m.mean, expected, 5 * m.stderr_ + 1e-5) << integ;
        EXPECT_GT(m.mean, 0.5 * expected) << integ;
    }
}

TEST(VolPathDepth, MaxDepthThreeAddsDoubleScattering) {
    // One more vertex adds double scattering, a positive amount: the test above would fail if the
    // medium allowed one vertex more than surfaces do.
    const double single = singleScattering();
    const Film f = test::renderXml(scene("volpath", 3), kRes, kRes, 1024, 23, true);
    const test::ImageMean m = test::imageMean(f, 1);
    EXPECT_GT(m.mean - single, 5 * m.stderr_);
}
