// Bidirectional path tracing (`bdpt`, issue 35) from outside and from inside. Outside: block
// z-tests against `path` (tests/support/agreement.h) for every light type in spectral and RGB mode,
// at several depth limits, with both heuristics and without the t = 1 or s = 1 strategies, through
// thin films, smooth shading normals and pass-through surfaces; an over-counting estimator (MIS
// weights removed) is rejected. Inside: the images of the strategies (s, t) add up to the image,
// and every strategy of one path length, unweighted, estimates that length by itself: they agree
// with each other. Determinism: thread count, resume, shards.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdio>

#include "integrators/bdpt.h"
#include "render/loader/scene_loader.h"
#include "render/renderer.h"
#include "render/scene.h"
#include "tests/support/agreement.h"
#include "tests/support/light_tracing_scenes.h"

using namespace iris;
using namespace iris::test;

namespace {

/// path on `xml` (another seed) against bdpt (`bdptSpp`; spec.edit applies to it only) on
/// `bdptXml` (default: the same scene).
Agreement bdptAgainstPath(const std::string& xml, RenderSpec spec, int bdptSpp, const std::string& bdptXml = "") {
    spec.defines["integrator"] = "path";
    RenderSpec ref = spec;
    ref.seed = spec.seed + 1000;
    ref.edit = nullptr;
    const Film path = renderLightTracingScene(xml, ref);
    spec.defines["integrator"] = "bdpt";
    spec.spp = bdptSpp;
    const Agreement a = compareFilms(renderLightTracingScene(bdptXml.empty() ? xml : bdptXml, spec), path);
    std::printf("[ bdpt ] |z| %.2f (threshold %.2f)\n", a.maxAbsZ, a.threshold);
    return a;
}

/// The scene with extra parameters in its integrator element (`$bdpt_extra` is not a Mitsuba
/// default: the XML is edited).
std::string withIntegratorParams(std::string xml, const std::string& params) {
    const std::string tag = "<integer name=\"max_depth\" value=\"$max_depth\"/>";
    xml.replace(xml.find(tag), tag.size(), tag + params);
    return xml;
}

std::string rectangleLight() { return testLights().at("area_rectangle"); }

class BDPTLights : public ::testing::TestWithParam<std::string> {};

TEST_P(BDPTLights, AgreesWithPathInBothModes) {
    const std::string xml = lightTracingScene(testLights().at(GetParam()));
    for (const bool rgb : {false, true}) {
        RenderSpec spec;
        spec.spp = 256;
        spec.rgb = rgb;
        const Agreement a = bdptAgainstPath(xml, spec, 128);
        EXPECT_TRUE(a.passed()) << GetParam() << (rgb ? " rgb" : " spectral") << ": |z| " << a.maxAbsZ << " >= " << a.threshold << " at "
                                << a.where;
    }
}

INSTANTIATE_TEST_SUITE_P(EveryType, BDPTLights,
                         ::testing::Values("point", "spot", "directional", "projector", "constant", "envmap", "area_rectangle",
                                           "area_sphere", "area_textured"));

TEST(BDPT, AgreesWithPathAtEveryDepthLimit) {
    const std::string xml = lightTracingScene(rectangleLight());
    for (const char* depth : {"1", "2", "4", "-1"}) {
        RenderSpec spec;
        spec.spp = 256;
        spec.defines["max_depth"] = depth;
        const Agreement a = bdptAgainstPath(xml, spec, 128);
        EXPECT_TRUE(a.passed()) << "max_depth " << depth << ": |z| " << a.maxAbsZ << " at " << a.where;
    }
}

TEST(BDPT, EveryStrategySetAndHeuristicAgrees) {
    const std::vector<std::string> variants = {
        "<string name=\"mis\" value=\"balance\"/>",
        "<boolean name=\"light_image\" value=\"false\"/>",
        "<boolean name=\"sample_direct\" value=\"false\"/>",
        "<boolean name=\"light_image\" value=\"false\"/><boolean name=\"sample_direct\" value=\"false\"/>",
    };
    for (const std::string& v : variants) {
        RenderSpec spec;
        spec.spp = 256;
        spec.defines["max_depth"] = "4";
        const std::string xml = lightTracingScene(testLights().at("area_sphere"));
        const Agreement a = bdptAgainstPath(xml, spec, 256, withIntegratorParams(xml, v));
        EXPECT_TRUE(a.passed()) << v << ": |z| " << a.maxAbsZ << " at " << a.where;
    }
}

TEST(BDPT, WithoutMISWeightsItIsRejected) {
    RenderSpec spec;
    spec.spp = 256;
    spec.edit = [](SceneDescription& d) {
        BDPTParams p;
        p.path.maxDepth = 3;
        auto b = std::make_shared<BDPTIntegrator>(p);
        b->disableMIS();
        d.integrator = b;
    };
    const Agreement a = bdptAgainstPath(lightTracingScene(rectangleLight()), spec, 64);
    EXPECT_FALSE(a.passed()) << "|z| " << a.maxAbsZ << " < " << a.threshold;
}

TEST(BDPT, ThinFilmsShadingNormalsAndMasksAgree) {
    const std::string extra = R"(<shape type="sphere"><point name="center" x="-0.8" y="0.45" z="0.7"/><float name="radius" value="0.45"/>
        <bsdf type="thinfilm"><string name="substrate_material" value="Au"/><float name="film_ior" value="1.45"/>
            <float name="thickness" value="420"/><float name="alpha" value="0.15"/></bsdf></shape>
        <shape type="sphere"><point name="center" x="0.9" y="0.35" z="0.9"/><float name="radius" value="0.35"/>
        <bsdf type="iridescent_diffuse"><rgb name="reflectance" value="0.6, 0.08, 0.05"/><float name="film_ior" value="1.9"/>
            <float name="thickness" value="250"/></bsdf></shape>
        <shape type="obj"><string name="filename" value=")" + lightTracingDataDir() + R"(/icosphere.obj"/>
        <transform name="to_world"><scale value="0.4"/><translate x="1.2" y="1.3" z="0.2"/></transform>
        <bsdf type="diffuse"><rgb name="reflectance" value="0.9"/></bsdf></shape>
        <shape type="rectangle"><transform name="to_world"><scale x="0.5" y="0.4"/><translate x="-0.3" y="1.4" z="1.6"/></transform>
        <bsdf type="mask"><float name="opacity" value="0.5"/><bsdf type="twosided"><bsdf type="diffuse"/></bsdf></bsdf></shape>)";
    for (const bool rgb : {false, true}) {
        RenderSpec spec;
        spec.spp = 512;
        spec.rgb = rgb;
        spec.defines["max_depth"] = "4";
        const Agreement a = bdptAgainstPath(lightTracingScene(testLights().at("area_sphere"), extra), spec, 256);
        EXPECT_TRUE(a.passed()) << (rgb ? "rgb" : "spectral") << ": |z| " << a.maxAbsZ << " at " << a.where;
    }
}

/// bdpt rendered with `strategy` = "s,t" (and mis_weights) on the rectangle-lit scene.
Film strategyImage(int s, int t, bool weighted, int spp, const std::string& maxDepth) {
    RenderSpec spec;
    spec.spp = spp;
    spec.rgb = true;
    spec.defines = {{"integrator", "bdpt"}, {"max_depth", maxDepth}};
    const std::string params = "<string name=\"strategy\" value=\"" + std::to_string(s) + "," + std::to_string(t) + "\"/>" +
                               (weighted ? "" : "<boolean name=\"mis_weights\" value=\"false\"/>");
    return renderLightTracingScene(withIntegratorParams(lightTracingScene(rectangleLight()), params), spec);
}

TEST(BDPT, StrategyImagesAddUpToTheImage) {
    RenderSpec spec;
    spec.spp = 4;
    spec.rgb = true;
    spec.defines = {{"integrator", "bdpt"}, {"max_depth", "3"}};
    const Film full = renderLightTracingScene(lightTracingScene(rectangleLight()), spec);
    std::vector<double> sum(full.meanImage().size(), 0.0);
    for (int length = 1; length <= 3; ++length)
        for (int s = 0; s <= length + 1; ++s) {
            const int t = length + 1 - s;
            if (t < 1 || (s == 1 && t == 1)) continue;
            const std::vector<float> img = strategyImage(s, t, true, 4, "3").meanImage();
            for (size_t i = 0; i < sum.size(); ++i) sum[i] += img[i];
        }
    const std::vector<float> ref = full.meanImage();
    double worst = 0;
    for (size_t i = 0; i < sum.size(); ++i) worst = std::max(worst, std::abs(sum[i] - ref[i]) / std::max(1e-6, double(ref[i])));
    EXPECT_LT(worst, 1e-5);  // float rounding of each image's pixel means
}

TEST(BDPT, EveryStrategyOfOnePathLengthEstimatesItAlone) {
    // Paths of 3 segments (4 vertices): (0,4) the camera subpath hits the light, (1,3) next-event
    // estimation, (2,2) an inner connection, (3,1) light tracing, (4,0) impossible. Unweighted,
    // each is an unbiased estimate of all light that arrives in exactly 3 segments.
    const Film base = strategyImage(0, 4, false, 1024, "3");
    for (const auto& [s, t] : {std::pair{1, 3}, std::pair{2, 2}, std::pair{3, 1}}) {
        const Agreement a = compareFilms(strategyImage(s, t, false, 1024, "3"), base);
        EXPECT_TRUE(a.passed()) << "strategy (" << s << "," << t << ") against (0,4): |z| " << a.maxAbsZ << " at " << a.where;
    }
    // ... and a strategy of another length does not agree with them (the test can fail).
    EXPECT_FALSE(compareFilms(strategyImage(1, 2, false, 1024, "3"), base).passed());
}

TEST(BDPT, IdenticalForAnyThreadCountAndResumable) {
    const std::string xml = lightTracingScene(testLights().at("area_sphere"));
    RenderSpec spec;
    spec.spp = 4;
    spec.defines = {{"integrator", "bdpt"}, {"res", "40"}};
    spec.threads = 1;
    const Film a = renderLightTracingScene(xml, spec);
    spec.threads = 3;
    const Film b = renderLightTracingScene(xml, spec);
    EXPECT_EQ(a.meanImage(), b.meanImage());

    const Scene scene(loadSceneFromString(xml, ".", spec.defines));
    const std::string ckpt = ::testing::TempDir() + "iris_bdpt_resume.ckpt";
    std::atomic<bool> cancel{false};
    RenderOptions first;
    first.spp = 4;
    first.seed = 1;
    first.checkpointPath = ckpt;
    first.threads = 1;
    first.onTileFinished = [&](uint64_t tiles, int perPass) { if (tiles == uint64_t(perPass + 3)) cancel = true; };
    Film part(40, 40);
    Renderer(scene, first).render(part, &cancel);
    RenderOptions second;
    second.spp = 4;
    second.seed = 1;
    second.checkpointPath = ckpt;
    second.resume = true;
    const Renderer r(scene, second);
    Film resumed(40, 40);
    resumed.load(ckpt, r.settingsKey());
    EXPECT_EQ(resumed.minSampleCount(), 1u);
    r.render(resumed);
    EXPECT_EQ(a.meanImage(), resumed.meanImage());
    std::remove(ckpt.c_str());
}

TEST(BDPT, BadParametersAndOrthographicSensorsAreRefused) {
    auto loadError = [](const std::string& xml) -> std::string {
        try {
            const Scene scene(loadSceneFromString(xml, ".", {{"integrator", "bdpt"}}));
            RenderOptions opt;
            opt.spp = 1;
            Film f(scene.description().camera.width, scene.description().camera.height);
            Renderer(scene, opt).render(f);
        } catch (const Error& e) {
            return e.what();
        }
        return "";
    };
    const std::string base = lightTracingScene(rectangleLight());
    EXPECT_NE(loadError(withIntegratorParams(base, "<string name=\"mis\" value=\"max\"/>")).find("mis must be 'power' or 'balance'"),
              std::string::npos);
    EXPECT_NE(loadError(withIntegratorParams(base, "<string name=\"strategy\" value=\"1,1\"/>")).find("strategy must be 's,t'"),
              std::string::npos);
    EXPECT_NE(loadError(withIntegratorParams(base, "<boolean name=\"mis_weights\" value=\"false\"/>")).find("needs a 'strategy'"),
              std::string::npos);
    const std::string ortho = lightTracingScene(rectangleLight(), "", R"(<sensor type="orthographic"><film type="hdrfilm">
        <integer name="width" value="8"/><integer name="height" value="8"/></film></sensor>)");
    EXPECT_NE(loadError(ortho).find("bdpt needs a perspective sensor"), std::string::npos) << loadError(ortho);
}

}  // namespace
