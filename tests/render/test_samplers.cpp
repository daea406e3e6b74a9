// The sampler plugins in renders: the scene's <sampler> and RenderOptions::sampler choose the
// sequence; images stay bit-identical for any thread count and when split into sample ranges;
// stratified, multijitter and Sobol points lower the error of an area-lit plane at equal spp
// (fixed seeds); unknown names are refused.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/error.h"
#include "render/film.h"
#include "render/loader/scene_loader.h"
#include "render/renderer.h"
#include "render/samplers/sampler_description.h"
#include "render/scene.h"

using namespace iris;

namespace {

/// A diffuse plane under a small square area light, seen from above; direct light only (max_depth
/// 2), so the error is that of sampling the light and the pixel.
std::string planeScene(const std::string& sampler) {
    return R"(<scene version="3.0.0">
  <integrator type="path"><integer name="max_depth" value="2"/></integrator>
  <sensor type="perspective">
    <float name="fov" value="50"/>
    <transform name="to_world"><lookat origin="0, 3, 0" target="0, 0, 0" up="0, 0, 1"/></transform>
    <film type="hdrfilm"><integer name="width" value="12"/><integer name="height" value="12"/>
      <rfilter type="box"/></film>
    )" + sampler + R"(
  </sensor>
  <shape type="rectangle">
    <transform name="to_world"><scale value="3"/><rotate x="1" angle="-90"/></transform>
    <bsdf type="diffuse"><rgb name="reflectance" value="0.2, 0.5, 0.8"/></bsdf>
  </shape>
  <shape type="rectangle">
    <transform name="to_world"><scale value="0.4"/><rotate x="1" angle="90"/><translate x="0.7" y="1.2" z="0.3"/></transform>
    <emitter type="area"><rgb name="radiance" value="8, 8, 8"/></emitter>
  </shape>
</scene>)";
}

SceneDescription load(const std::string& sampler) { return loadSceneFromString(planeScene(sampler), "."); }

std::vector<float> render(const Scene& scene, RenderOptions opt, int first = 0, int count = -1, Film* into = nullptr) {
    const CameraDescription& c = scene.description().camera;
    Film film(c.width, c.height);
    opt.firstSample = first;
    if (count >= 0) opt.spp = count;
    Renderer(scene, opt).render(into ? *into : film);
    return (into ? *into : film).meanImage();
}

double mse(const std::vector<float>& a, const std::vector<float>& b) {
    double s = 0;
    for (size_t i = 0; i < a.size(); ++i) s += (double(a[i]) - b[i]) * (double(a[i]) - b[i]);
    return s / double(a.size());
}

const char* const kSequences[] = {"independent", "stratified", "multijitter", "sobol", "highdimsobol"};
constexpr int kSequenceCount = 5;

}  // namespace

TEST(Samplers, SceneSamplerChoosesTheSequence) {
    EXPECT_EQ(load(R"(<sampler type="stratified"><integer name="sample_count" value="9"/>
                      <boolean name="jitter" value="false"/></sampler>)").samplePattern.sequence,
              SampleSequence::Stratified);
    const SceneDescription mj = load(R"(<sampler type="multijitter"/>)");
    EXPECT_EQ(mj.samplePattern.sequence, SampleSequence::Multijitter);
    EXPECT_TRUE(mj.samplePattern.jitter);
    EXPECT_EQ(load(R"(<sampler type="sobol"/>)").samplePattern.sequence, SampleSequence::Sobol);
    EXPECT_EQ(load(R"(<sampler type="ldsampler"/>)").samplePattern.sequence, SampleSequence::Sobol);
    EXPECT_EQ(load(R"(<sampler type="highdimsobol"/>)").samplePattern.sequence, SampleSequence::HighDimSobol);
    EXPECT_EQ(load(R"(<sampler type="halton"/>)").samplePattern.sequence, SampleSequence::Independent);
    EXPECT_FALSE(load(R"(<sampler type="stratified"><boolean name="jitter" value="false"/></sampler>)").samplePattern.jitter);
}

TEST(Samplers, UnknownSamplerIsRefused) {
    const Scene scene(load(""));
    RenderOptions opt;
    opt.sampler = "halton2";
    try {
        Renderer r(scene, opt);
        ADD_FAILURE() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("unknown sampler 'halton2'"), std::string::npos) << e.what();
    }
    EXPECT_THROW(loadSceneFromString(planeScene(R"(<sampler type="sobol"><integer name="sample_count" value="0"/></sampler>)"), "."),
                 Error);
}

TEST(Samplers, ImagesDoNotDependOnThreadsAndSplitRendersMatchBitForBit) {
    const Scene scene(load(""));
    for (const char* name : kSequences) {
        RenderOptions opt;
        opt.sampler = name;
        opt.seed = 3;
        opt.spp = 12;
        opt.patternSize = 12;
        opt.threads = 1;
        const std::vector<float> one = render(scene, opt);
        opt.threads = 2;
        EXPECT_EQ(render(scene, opt), one) << name;
        // Samples 0..4 and 5..11 in two films added up: the unsplit image.
        const CameraDescription& c = scene.description().camera;
        Film a(c.width, c.height), b(c.width, c.height);
        render(scene, opt, 0, 5, &a);
        render(scene, opt, 5, 7, &b);
        a.add(b);
        EXPECT_EQ(a.meanImage(), one) << name;
    }
}

TEST(Samplers, SettingsKeyNamesTheSamplerAndItsPattern) {
    const Scene scene(load(""));
    RenderOptions opt;
    const std::string independent = Renderer(scene, opt).settingsKey();
    EXPECT_EQ(independent.find("sampler="), std::string::npos);  // earlier checkpoints stay valid
    opt.sampler = "stratified";
    opt.patternSize = 16;
    EXPECT_NE(Renderer(scene, opt).settingsKey().find(";sampler=stratified/16"), std::string::npos);
    opt.patternSize = 32;
    EXPECT_NE(Renderer(scene, opt).settingsKey().find(";sampler=stratified/32"), std::string::npos);
}

// Variance reduction at equal spp on the area-lit plane: the error of 16 spp against a 4096-spp
// reference, summed over 8 seeds, in spectral mode (the wavelength request is stratified too) and
// RGB mode. Each low-discrepancy sampler must at least halve the independent sampler's error.
TEST(Samplers, StratifiedPointsLowerTheErrorAtEqualSpp) {
    const Scene scene(load(""));
    for (const bool rgb : {false, true}) {
        RenderOptions ref;
        ref.rgbMode = rgb;
        ref.spp = 4096;
        ref.sampler = "sobol";
        ref.seed = 1000;
        const std::vector<float> reference = render(scene, ref);
        double err[kSequenceCount] = {};
        for (int k = 0; k < kSequenceCount; ++k)
            for (uint64_t seed = 1; seed <= 8; ++seed) {
                RenderOptions opt;
                opt.rgbMode = rgb;
                opt.spp = 16;
                opt.patternSize = 16;
                opt.sampler = kSequences[k];
                opt.seed = seed;
                err[k] += mse(render(scene, opt), reference);
            }
        for (int k = 1; k < kSequenceCount; ++k)
            EXPECT_LT(err[k], 0.5 * err[0]) << kSequences[k] << (rgb ? " rgb" : " spectral") << ": " << err[k] << " vs independent " << err[0];
        std::printf("[ samplers ] %s mode, MSE x 8 seeds at 16 spp: independent %.4g stratified %.4g multijitter %.4g sobol %.4g "
                    "highdimsobol %.4g\n", rgb ? "rgb" : "spectral", err[0], err[1], err[2], err[3], err[4]);
    }
}
