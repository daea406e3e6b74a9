// Shading normals and the strict_normals option (integrators/transport_steps.h, sidesAgree).
// Mitsuba 3 follows every direction a BSDF samples and lights every direction next-event estimation
// picks, whatever side of the geometric surface it lies on; Mitsuba 0.6 does the same unless its
// integrator sets strictNormals. Oracle: a diffuse quad whose vertex normals are tilted 60° from its
// face normal, under a uniform environment of radiance 1, is a white furnace in the shading frame:
// it reflects exactly its albedo when nothing is discarded, and less with strict_normals.
#include <gtest/gtest.h>

#include <string>

#include "tests/support/app_runner.h"
#include "tests/support/image_mean.h"

using namespace iris;

namespace {

constexpr int kRes = 8;

/// The tilted quad written as an OBJ file: face normal +z, vertex normals (sin 60°, 0, cos 60°).
std::string tiltedQuad() {
    const std::string path = iris::testing::tempPath("iris_strict_normals", "quad.obj");
    iris::testing::writeTextFile(path, "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvn 0.8660254 0 0.5\n"
                                 "f 1//1 2//1 3//1\nf 1//1 3//1 4//1\n");
    return path;
}

std::string scene(const std::string& integ, const std::string& strict) {
    return R"(<scene version="3.0.0">
  <integrator type=")" + integ + R"(">)" + strict + R"(</integrator>
  <sensor type="perspective"><float name="fov" value="1"/>
    <transform name="to_world"><lookat origin="0 0 3" target="0 0 0" up="0 1 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/><rfilter type="box"/></film></sensor>
  <emitter type="constant"><float name="radiance" value="1"/></emitter>
  <shape type="obj"><string name="filename" value=")" + tiltedQuad() + R"("/>
    <bsdf type="diffuse"><float name="reflectance" value="0.5"/></bsdf></shape>
</scene>)";
}

}  // namespace

TEST(StrictNormals, OffByDefaultAsInMitsuba) {
    for (const char* integ : {"path", "volpath"}) {
        const Film f = test::renderXml(scene(integ, ""), kRes, kRes, 1024, 3, true);
        const test::ImageMean m = test::imageMean(f, 1);
        EXPECT_NEAR(m.mean, 0.5, 5 * m.stderr_ + 1e-4) << integ;
    }
}

TEST(StrictNormals, OnDiscardsDirectionsAcrossTheGeometricSurface) {
    // The same furnace loses the directions whose geometric and shading sides disagree: the
    // default's closed form fails here, so the option is seen to act.
    for (const char* integ : {"path", "volpath"}) {
        const Film f = test::renderXml(scene(integ, R"(<boolean name="strict_normals" value="true"/>)"), kRes, kRes, 1024, 3, true);
        const test::ImageMean m = test::imageMean(f, 1);
        EXPECT_LT(m.mean, 0.5 - 5 * m.stderr_ - 0.02) << integ;
        EXPECT_GT(m.mean, 0.1) << integ;
    }
}
