// The particle tracer (`ptracer`, issue 35) against the path tracer: block z-tests of the two
// estimators on small scenes (tests/support/agreement.h), for every light type, in spectral and RGB
// mode, with smooth shading normals, an orthographic sensor, thin films and pass-through surfaces;
// the tests prove they can fail (a perturbed light, Veach's shading-normal correction removed).
// Determinism: bit-identical films for any thread count, resumed from a checkpoint, and from
// shards of the sample range.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdio>

#include "integrators/path.h"
#include "integrators/ptracer.h"
#include "render/loader/scene_loader.h"
#include "render/renderer.h"
#include "render/scene.h"
#include "tests/support/agreement.h"
#include "tests/support/light_tracing_scenes.h"

using namespace iris;
using namespace iris::test;

namespace {

/// path (reference, another seed) against ptracer (`ptracerSpp` samples; spec.edit applies to it
/// only) on `xml`.
Agreement ptracerAgainstPath(const std::string& xml, RenderSpec spec, int ptracerSpp) {
    spec.defines["integrator"] = "path";
    RenderSpec ref = spec;
    ref.seed = spec.seed + 1000;
    ref.edit = nullptr;
    const Film path = renderLightTracingScene(xml, ref);
    spec.defines["integrator"] = "ptracer";
    spec.spp = ptracerSpp;
    const Film pt = renderLightTracingScene(xml, spec);
    const Agreement a = compareFilms(pt, path);
    std::printf("[ ptracer ] |z| %.2f (threshold %.2f)\n", a.maxAbsZ, a.threshold);
    return a;
}

std::string rectangleLight() { return testLights().at("area_rectangle"); }

class PTracerLights : public ::testing::TestWithParam<std::string> {};

TEST_P(PTracerLights, AgreesWithPathInBothModes) {
    const std::string xml = lightTracingScene(testLights().at(GetParam()));
    for (const bool rgb : {false, true}) {
        RenderSpec spec;
        spec.spp = 256;
        spec.rgb = rgb;
        const Agreement a = ptracerAgainstPath(xml, spec, 512);
        EXPECT_TRUE(a.passed()) << GetParam() << (rgb ? " rgb" : " spectral") << ": |z| " << a.maxAbsZ << " >= " << a.threshold << " at "
                                << a.where;
    }
}

INSTANTIATE_TEST_SUITE_P(EveryType, PTracerLights,
                         ::testing::Values("point", "spot", "directional", "projector", "constant", "envmap", "area_rectangle",
                                           "area_sphere", "area_textured"));

TEST(PTracer, AgreesWithPathAtEveryDepthLimit) {
    const std::string xml = lightTracingScene(rectangleLight());
    for (const char* depth : {"1", "2", "-1"}) {
        RenderSpec spec;
        spec.spp = 128;
        spec.defines["max_depth"] = depth;
        const Agreement a = ptracerAgainstPath(xml, spec, 512);
        EXPECT_TRUE(a.passed()) << "max_depth " << depth << ": |z| " << a.maxAbsZ << " at " << a.where;
    }
}

TEST(PTracer, APerturbedLightIsRejected) {
    // The same test with the ptracer's light 4 % brighter than the reference's fails.
    const std::string dim = lightTracingScene(rectangleLight());
    std::string bright = dim;
    bright.replace(bright.find("value=\"8\""), 9, "value=\"8.32\"");
    RenderSpec spec;
    spec.spp = 256;
    spec.defines["integrator"] = "path";
    const Film path = renderLightTracingScene(dim, spec);
    spec.defines["integrator"] = "ptracer";
    spec.spp = 1024;
    const Agreement a = compareFilms(renderLightTracingScene(bright, spec), path);
    std::printf("[ ptracer ] light 4 %% brighter: |z| %.2f (threshold %.2f)\n", a.maxAbsZ, a.threshold);
    EXPECT_FALSE(a.passed()) << "|z| " << a.maxAbsZ << " < " << a.threshold;
}

/// A coarse sphere with smooth vertex normals on the floor: light tracing needs Veach's correction
/// of the adjoint BSDF (eq. 5.19) to estimate what path tracing does.
/// A small spherical light in front of the scene, to the left of the camera.
const std::string kFrontLight = R"(<shape type="sphere"><point name="center" x="-1.2" y="1.7" z="2.8"/><float name="radius" value="0.25"/>
    <emitter type="area"><rgb name="radiance" value="12"/></emitter></shape>)";

std::string smoothMeshScene() {
    return lightTracingScene(kFrontLight,
                             "<shape type=\"obj\"><string name=\"filename\" value=\"" + lightTracingDataDir() +
                                 "/icosphere.obj\"/><transform name=\"to_world\"><scale value=\"0.7\"/>"
                                 "<translate x=\"0.1\" y=\"0.75\" z=\"1.3\"/></transform>"
                                 "<bsdf type=\"diffuse\"><rgb name=\"reflectance\" value=\"0.9\"/></bsdf></shape>");
}

TEST(PTracer, ShadingNormalsNeedVeachsCorrection) {
    const std::string xml = smoothMeshScene();
    RenderSpec spec;
    spec.spp = 512;
    spec.defines["max_depth"] = "2";
    const Agreement with = ptracerAgainstPath(xml, spec, 2048);
    EXPECT_TRUE(with.passed()) << "|z| " << with.maxAbsZ << " at " << with.where;
    spec.edit = [](SceneDescription& d) {
        PathParams params;
        params.maxDepth = 2;
        auto pt = std::make_shared<PTracerIntegrator>(params, -1);
        pt->disableShadingCorrection();
        d.integrator = pt;
    };
    const Agreement without = ptracerAgainstPath(xml, spec, 2048);
    std::printf("[ ptracer ] shading normals: with the correction |z| %.2f, without %.2f (threshold %.2f)\n", with.maxAbsZ,
                without.maxAbsZ, with.threshold);
    EXPECT_FALSE(without.passed()) << "without the correction: |z| " << without.maxAbsZ << " < " << without.threshold;
}

TEST(PTracer, OrthographicSensorAgrees) {
    const std::string sensor = R"(<sensor type="orthographic"><transform name="to_world">
        <lookat origin="0, 1.2, 4.5" target="0, 0.8, 0" up="0, 1, 0"/><scale x="1.6" y="1.6"/></transform>
        <film type="hdrfilm"><integer name="width" value="$res"/><integer name="height" value="$res"/><rfilter type="box"/></film></sensor>)";
    RenderSpec spec;
    spec.spp = 256;
    const Agreement a = ptracerAgainstPath(lightTracingScene(rectangleLight(), "", sensor), spec, 1024);
    EXPECT_TRUE(a.passed()) << "|z| " << a.maxAbsZ << " at " << a.where;
}

TEST(PTracer, GaussianFilterSplatsAgree) {
    RenderSpec spec;
    spec.spp = 256;
    const Agreement a = ptracerAgainstPath(lightTracingScene(rectangleLight(), "", perspectiveSensor("<rfilter type=\"gaussian\"/>")), spec, 512);
    EXPECT_TRUE(a.passed()) << "|z| " << a.maxAbsZ << " at " << a.where;
}

TEST(PTracer, ThinFilmsAgree) {
    const std::string films = R"(<shape type="sphere"><point name="center" x="-0.8" y="0.45" z="0.7"/><float name="radius" value="0.45"/>
        <bsdf type="thinfilm"><string name="substrate_material" value="Au"/><float name="film_ior" value="1.45"/>
            <float name="thickness" value="420"/><float name="alpha" value="0.15"/></bsdf></shape>
        <shape type="sphere"><point name="center" x="0.9" y="0.35" z="0.9"/><float name="radius" value="0.35"/>
        <bsdf type="iridescent_diffuse"><rgb name="reflectance" value="0.6, 0.08, 0.05"/><float name="film_ior" value="1.9"/>
            <float name="thickness" value="250"/><float name="alpha" value="0.2"/></bsdf></shape>)";
    for (const bool rgb : {false, true}) {
        RenderSpec spec;
        spec.spp = 256;
        spec.rgb = rgb;
        const Agreement a = ptracerAgainstPath(lightTracingScene(rectangleLight(), films), spec, 1024);
        EXPECT_TRUE(a.passed()) << (rgb ? "rgb" : "spectral") << ": |z| " << a.maxAbsZ << " at " << a.where;
    }
}

TEST(PTracer, PassThroughSurfacesAgree) {
    // A half-transparent mask in front of the scene: the connections cross it with its weight and
    // count it as a segment, as `path` does. The mask also blocks the path tracer's shadow rays
    // (Mitsuba's convention), so the floor in its shadow is found by BSDF sampling only, a rare
    // event: the reference needs more samples there.
    const std::string mask = R"(<shape type="rectangle"><transform name="to_world"><scale x="0.6" y="0.5"/><translate x="-0.2" y="0.9" z="1.6"/></transform>
        <bsdf type="mask"><float name="opacity" value="0.5"/><bsdf type="twosided"><bsdf type="diffuse"/></bsdf></bsdf></shape>)";
    for (const char* depth : {"2", "3"}) {
        RenderSpec spec;
        spec.spp = 1024;
        spec.defines["max_depth"] = depth;
        const Agreement a = ptracerAgainstPath(lightTracingScene(rectangleLight(), mask), spec, 1024);
        EXPECT_TRUE(a.passed()) << "max_depth " << depth << ": |z| " << a.maxAbsZ << " at " << a.where;
    }
}

TEST(PTracer, IdenticalForAnyThreadCount) {
    const std::string xml = lightTracingScene(testLights().at("area_sphere"));
    RenderSpec spec;
    spec.spp = 6;
    spec.defines["integrator"] = "ptracer";
    spec.threads = 1;
    const Film a = renderLightTracingScene(xml, spec);
    spec.threads = 2;
    const Film b = renderLightTracingScene(xml, spec);
    spec.threads = 5;
    const Film c = renderLightTracingScene(xml, spec);
    EXPECT_EQ(a.meanImage(), b.meanImage());
    EXPECT_EQ(a.meanImage(), c.meanImage());
    EXPECT_EQ(a.secondMomentImage(), c.secondMomentImage());
    spec.seed = 2;  // the test can fail
    EXPECT_NE(a.meanImage(), renderLightTracingScene(xml, spec).meanImage());
}

/// The ptracer scene, loaded at 40×40 pixels (9 tiles a pass).
Scene ptracerScene() {
    return Scene(loadSceneFromString(lightTracingScene(rectangleLight()), ".", {{"integrator", "ptracer"}, {"res", "40"}}));
}

TEST(PTracer, ResumeAndShardsAreBitExact) {
    const Scene scene = ptracerScene();
    RenderOptions opt;
    opt.seed = 5;
    opt.spp = 8;
    Film full(40, 40);
    Renderer(scene, opt).render(full);

    // Interrupted in the middle of its fourth pass, then resumed from the checkpoint.
    const std::string ckpt = ::testing::TempDir() + "iris_ptracer_resume.ckpt";
    std::atomic<bool> cancel{false};
    RenderOptions first = opt;
    first.checkpointPath = ckpt;
    first.onTileFinished = [&](uint64_t tiles, int perPass) { if (tiles == uint64_t(2 * perPass + 4)) cancel = true; };
    first.threads = 1;
    Film part(40, 40);
    const RenderStats st = Renderer(scene, first).render(part, &cancel);
    EXPECT_TRUE(st.interrupted);
    EXPECT_EQ(st.sppMax, 2u);  // the third pass was stopped: its splats are dropped
    RenderOptions second = opt;
    second.checkpointPath = ckpt;
    second.resume = true;
    const Renderer r(scene, second);
    Film resumed(40, 40);
    resumed.load(ckpt, r.settingsKey());
    EXPECT_EQ(resumed.minSampleCount(), 2u);
    r.render(resumed);
    EXPECT_EQ(full.meanImage(), resumed.meanImage());
    std::remove(ckpt.c_str());

    // Shards of the sample range add up to the unsplit film.
    Film sum(40, 40);
    for (const auto& [a, b] : {std::pair{0, 3}, std::pair{3, 8}}) {
        RenderOptions shard = opt;
        shard.firstSample = a;
        shard.spp = b - a;
        Film f(40, 40);
        Renderer(scene, shard).render(f);
        sum.add(f);
    }
    EXPECT_EQ(full.meanImage(), sum.meanImage());
}

TEST(PTracer, SpectralOutputAndMediaAreRefusedWithAReason) {
    const Scene scene = ptracerScene();
    RenderOptions opt;
    opt.spp = 1;
    Film film(40, 40);
    SpectralFilm spectral(40, 40, SpectralBins(10.0));
    try {
        Renderer(scene, opt).render(film, nullptr, &spectral);
        ADD_FAILURE() << "a spectral image was rendered with ptracer";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("not available with the 'ptracer' integrator"), std::string::npos) << e.what();
    }
    const std::string medium = lightTracingScene(rectangleLight(), R"(<shape type="sphere"><float name="radius" value="0.2"/>
        <medium type="homogeneous" name="interior"><rgb name="sigma_t" value="1"/></medium><bsdf type="null"/></shape>)");
    try {
        loadSceneFromString(medium, ".", {{"integrator", "ptracer"}});
        ADD_FAILURE() << "a scene with media was loaded with ptracer";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("participating media"), std::string::npos) << e.what();
    }
}

}  // namespace
