// The sensors' importance for light tracing (Sensor::sampleWi, pdfDirection; issue 35): a point on
// a camera ray is seen at the film position the ray came from, the weight is W H / (A cos³θ d²)
// (perspective) or W H / A⊥ (orthographic), the directional density integrates to 1 over the image,
// and points behind the sensor are not seen.
#include <gtest/gtest.h>

#include "core/rng.h"
#include "core/sampling.h"
#include "render/loader/scene_loader.h"
#include "render/scene.h"
#include "tests/support/light_tracing_scenes.h"

using namespace iris;

namespace {

const Sensor& sensorOf(const Scene& s) { return *s.description().camera.sensor; }

TEST(SensorImportance, PerspectiveSeesRayPointsWhereTheRaysStart) {
    const Scene scene(loadSceneFromString(test::lightTracingScene(test::testLights().at("point")), ".", {{"res", "24"}}));
    const Sensor& sensor = sensorOf(scene);
    Sampler rng(3);
    for (int i = 0; i < 200; ++i) {
        const vec2 pos = rng.get2D() * 24.0f;
        const Ray ray = sensor.generateRay(pos);
        const float d = 0.5f + 5.0f * rng.get1D();
        const std::optional<SensorSample> s = sensor.sampleWi(ray.at(d));
        ASSERT_TRUE(s);
        EXPECT_NEAR(s->filmPos.x, pos.x, 2e-3f);
        EXPECT_NEAR(s->filmPos.y, pos.y, 2e-3f);
        EXPECT_NEAR(glm::dot(s->wi, -ray.d), 1.0f, 1e-5f);
        EXPECT_NEAR(s->weight, 24.0f * 24.0f * sensor.pdfDirection(ray.d) / (d * d), 1e-4f * s->weight);
    }
    EXPECT_FALSE(sensor.sampleWi(*sensor.pinhole() - 2.0f * sensor.generateRay(vec2(12.0f)).d));  // behind
}

TEST(SensorImportance, PerspectiveDensityIntegratesToOneOverTheImage) {
    const Scene scene(loadSceneFromString(test::lightTracingScene(test::testLights().at("point")), ".", {{"res", "24"}}));
    const Sensor& sensor = sensorOf(scene);
    Sampler rng(5);
    const int n = 400000;
    double s1 = 0, s2 = 0;
    for (int i = 0; i < n; ++i) {
        const vec3 w = sampleUniformSphere(rng.get2D());
        const std::optional<SensorSample> s = sensor.sampleWi(*sensor.pinhole() + w);
        const bool inImage = s && s->filmPos.x >= 0 && s->filmPos.x < 24 && s->filmPos.y >= 0 && s->filmPos.y < 24;
        const double v = inImage ? sensor.pdfDirection(w) / uniformSpherePdf() : 0.0;
        s1 += v;
        s2 += v * v;
    }
    const double mean = s1 / n, se = std::sqrt((s2 / n - mean * mean) / (n - 1));
    EXPECT_NEAR(mean, 1.0, 5 * se);
}

TEST(SensorImportance, OrthographicWeightIsPixelsOverTheWindowArea) {
    const std::string sensorXml = R"(<sensor type="orthographic"><transform name="to_world">
        <lookat origin="0, 1, 4" target="0, 1, 0" up="0, 1, 0"/><scale x="1.5" y="1.5"/></transform>
        <film type="hdrfilm"><integer name="width" value="32"/><integer name="height" value="16"/></film></sensor>)";
    const Scene scene(loadSceneFromString(test::lightTracingScene(test::testLights().at("point"), "", sensorXml), "."));
    const Sensor& sensor = sensorOf(scene);
    // The window x ∈ [−1, 1], y ∈ [−1/aspect, 1/aspect] scaled by 1.5: A⊥ = 4 · 1.5² / 2.
    const float area = 4.0f * 1.5f * 1.5f / 2.0f;
    Sampler rng(9);
    for (int i = 0; i < 100; ++i) {
        const vec2 pos = rng.get2D() * vec2(32.0f, 16.0f);
        const Ray ray = sensor.generateRay(pos);
        const std::optional<SensorSample> s = sensor.sampleWi(ray.at(1.0f + 3.0f * rng.get1D()));
        ASSERT_TRUE(s);
        EXPECT_NEAR(s->filmPos.x, pos.x, 2e-3f);
        EXPECT_NEAR(s->filmPos.y, pos.y, 2e-3f);
        EXPECT_NEAR(s->weight, 32.0f * 16.0f / area, 1e-3f);
    }
    EXPECT_FALSE(sensor.pinhole());
}

}  // namespace
