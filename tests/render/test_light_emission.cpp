// Emission sampling of every light type (Light::sampleLe / pdfLe, issue 35): the densities sampleLe
// reports are those pdfLe gives for its rays, and the mean of the rays' throughput weights is the
// light's emitted power (the flux through the scene's disk for lights at infinity), analytic here.
#include <gtest/gtest.h>

#include "core/rng.h"
#include "render/loader/scene_loader.h"
#include "render/scene.h"
#include "tests/support/light_tracing_scenes.h"

using namespace iris;

namespace {

struct PowerCase {
    std::string name;
    double power;  // analytic, for the light of testLights() (RGB mode, channel 1 = green)
};

/// The flux estimate E[Le |cos| / (pdfPos pdfDir)] and its standard error, and the largest relative
/// difference between sampleLe's densities and pdfLe's for the same ray.
struct EmissionStats {
    double mean = 0, stderr_ = 0;
    float densityError = 0;
};

EmissionStats emissionStats(const Scene& scene, const Light& light, int n) {
    const SampledWavelengths wl = SampledWavelengths::rgb(defaultChannelWavelengths());
    Sampler rng(17);
    EmissionStats s;
    double s1 = 0, s2 = 0;
    for (int i = 0; i < n; ++i) {
        const vec2 uPos = rng.get2D(), uDir = rng.get2D();
        const std::optional<LightEmission> e = light.sampleLe(uPos, uDir, wl, scene.bounds());
        if (!e) continue;
        const double w = e->weight()[1];
        s1 += w;
        s2 += w * w;
        const vec2 pdf = light.pdfLe(e->at.p, e->n, e->ray.d, scene.bounds());
        if (!light.isDelta()) s.densityError = std::max(s.densityError, std::abs(pdf.x - e->pdfPos) / e->pdfPos);
        if (light.type() != Light::Type::DeltaDirection) s.densityError = std::max(s.densityError, std::abs(pdf.y - e->pdfDir) / e->pdfDir);
    }
    s.mean = s1 / n;
    s.stderr_ = std::sqrt(std::max(0.0, s2 / n - s.mean * s.mean) / (n - 1));
    return s;
}

TEST(LightEmission, DensitiesAgreeAndWeightsAverageToThePower) {
    const double pi = 3.14159265358979;
    const std::vector<PowerCase> cases = {
        {"point", 4 * pi * 4},                 // 4π I
        {"area_rectangle", pi * 8 * 0.8 * 0.8},  // π L A
        {"area_sphere", pi * 5 * 4 * pi * 0.25 * 0.25},
        {"constant", -1},  // π R² · 4π · L, R from the scene's bounds (below)
        {"directional", -2},  // π R² · E
    };
    for (const PowerCase& c : cases) {
        const Scene scene(loadSceneFromString(test::lightTracingScene(test::testLights().at(c.name)), "."));
        const Light* light = nullptr;
        for (const LightPtr& l : scene.lights())
            if (c.name.rfind("area", 0) == 0 ? l->type() == Light::Type::Area : l->type() != Light::Type::Area) light = l.get();
        ASSERT_TRUE(light) << c.name;
        const double r2 = double(scene.bounds().radius) * scene.bounds().radius;
        const double power = c.power == -1 ? pi * r2 * 4 * pi * 0.7 : c.power == -2 ? pi * r2 * 1.5 : c.power;
        const EmissionStats s = emissionStats(scene, *light, 200000);
        EXPECT_NEAR(s.mean, power, 5 * s.stderr_ + 1e-4 * power) << c.name;
        EXPECT_LT(s.densityError, 1e-4f) << c.name;
    }
}

TEST(LightEmission, SpotAndProjectorRaysStayInTheirCones) {
    for (const char* name : {"spot", "projector"}) {
        const Scene scene(loadSceneFromString(test::lightTracingScene(test::testLights().at(name)), "."));
        const Light& light = *scene.lights().back();
        const EmissionStats s = emissionStats(scene, light, 20000);
        EXPECT_GT(s.mean, 0.0) << name;
        EXPECT_LT(s.densityError, 1e-4f) << name;
        // A direction outside the cone has density 0.
        const vec2 behind = light.pdfLe(vec3(0.0f), vec3(0.0f), glm::normalize(vec3(0, 1, 0)), scene.bounds());
        EXPECT_EQ(behind.y, 0.0f) << name;
    }
}

}  // namespace
