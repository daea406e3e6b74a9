// Mitsuba's moment integrator wrapper: it renders exactly what its nested integrator renders, and
// the film's second moment is the mean of the squared samples.
#include <gtest/gtest.h>

#include "render/film.h"
#include "render/loader/scene_loader.h"
#include "render/renderer.h"
#include "render/scene.h"

using namespace iris;

namespace {
const char* kScene = R"(<scene version="3.0.0">
  %s
  <sensor type="perspective"><float name="fov" value="40"/>
    <transform name="to_world"><lookat origin="0 0 -4" target="0 0 0" up="0 1 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/></film></sensor>
  <emitter type="constant"><float name="radiance" value="1"/></emitter>
  <shape type="sphere"><bsdf type="diffuse"><float name="reflectance" value="0.5"/></bsdf></shape>
</scene>)";

Film render(const std::string& integrator) {
    char buf[2048];
    std::snprintf(buf, sizeof buf, kScene, integrator.c_str());
    const Scene scene(loadSceneFromString(buf, "."));
    RenderOptions opt;
    opt.spp = 4;
    opt.seed = 3;
    opt.rgbMode = true;
    Film film(8, 8);
    Renderer(scene, opt).render(film);
    return film;
}
}  // namespace

TEST(MomentIntegrator, RendersTheNestedIntegratorAndItsSecondMoment) {
    const Film moment = render(R"(<integrator type="moment"><integrator type="path"><integer name="max_depth" value="3"/></integrator></integrator>)");
    const Film path = render(R"(<integrator type="path"><integer name="max_depth" value="3"/></integrator>)");
    EXPECT_EQ(moment.meanImage(), path.meanImage());
    const std::vector<float> m1 = moment.meanImage(), m2 = moment.secondMomentImage(), var = moment.varianceOfMeanImage();
    // Var of the mean = (m2 − m1²) · n / (n − 1) / n with n = 4 samples per pixel.
    for (size_t i = 0; i < m1.size(); ++i) {
        EXPECT_GE(m2[i] + 1e-6f, m1[i] * m1[i]);
        EXPECT_NEAR(var[i], (m2[i] - m1[i] * m1[i]) / 3.0f, 1e-4f * (1.0f + m2[i]));
    }
}

TEST(MomentIntegrator, NeedsOneNestedIntegrator) {
    const std::string noNested = R"(<scene version="3.0.0"><integrator type="moment"/></scene>)";
    EXPECT_THROW(loadSceneFromString(noNested, "."), Error);
    const std::string unknownNested = R"(<scene version="3.0.0"><integrator type="moment"><integrator type="sppm"/></integrator></scene>)";
    EXPECT_THROW(loadSceneFromString(unknownNested, "."), Error);
}
