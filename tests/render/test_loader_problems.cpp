// A scene file with several problems reports all of them in one error (one "file:line:" line
// each), and a Mitsuba plugin iris cannot honour names what to use instead.
#include <gtest/gtest.h>

#include "render/loader/scene_loader.h"
#include "tests/support/error_of.h"

using namespace iris;

namespace {
std::string loadError(const std::string& body, const std::string& version = "3.0.0") { return test::sceneError(body, version); }
const auto has = test::contains;
}  // namespace

TEST(LoaderProblems, EveryProblemOfAFileAtOnce) {
    const std::string msg = loadError(
        "<integrator type=\"path\"><integer name=\"maxdepth\" value=\"3\"/><boolean name=\"bogus\" value=\"true\"/></integrator>\n"
        "<sensor type=\"perspective\"><film type=\"hdrfilm\"><rfilter type=\"sinc\"/></film></sensor>\n"
        "<shape type=\"sphere\"><bsdf type=\"plasticky\"/></shape>\n"
        "<shape type=\"torus\"/>\n");
    EXPECT_TRUE(has(msg, "<string>:2: unknown parameter 'maxdepth'")) << msg;
    EXPECT_TRUE(has(msg, "<string>:2: unknown parameter 'bogus'")) << msg;  // both unknown parameters
    EXPECT_TRUE(has(msg, "<string>:3: unknown rfilter type 'sinc'")) << msg;
    EXPECT_TRUE(has(msg, "<string>:4: unknown bsdf type 'plasticky'")) << msg;
    EXPECT_TRUE(has(msg, "<string>:5: unknown shape type 'torus'")) << msg;
    EXPECT_EQ(std::count(msg.begin(), msg.end(), '\n'), 4) << msg;  // five lines, one per problem
}

TEST(LoaderProblems, AMitsuba06FileWithStrictNormalsLoads) {
    EXPECT_EQ(loadError("<integrator type=\"path\"><boolean name=\"strictNormals\" value=\"true\"/></integrator>\n", "0.6.0"), "");
}

TEST(LoaderProblems, UnhonouredPluginsSayWhatToUseInstead) {
    const std::string hair = loadError("<shape type=\"sphere\">\n<bsdf type=\"hair\"/></shape>\n");
    EXPECT_TRUE(has(hair, "<string>:3: unknown bsdf type 'hair'")) << hair;
    EXPECT_TRUE(has(hair, "roughconductor")) << hair;
    EXPECT_TRUE(has(loadError("<emitter type=\"sun\"/>\n"), "use 'directional'"));
    EXPECT_TRUE(has(loadError("<shape type=\"linearcurve\"/>\n"), "convert the curves to a mesh"));
    EXPECT_TRUE(has(loadError("<sensor type=\"thinlens\"/>\n"), "use 'perspective'"));
    // A type in capitals (files written where the file system ignores case) names the plugin.
    const std::string caps = loadError("<shape type=\"Rectangle\"/>\n");
    EXPECT_TRUE(has(caps, "<string>:2: unknown shape type 'Rectangle'") && has(caps, "write 'rectangle'")) << caps;
    EXPECT_FALSE(has(loadError("<shape type=\"Rectangel\"/>\n"), "lower case"));
    // mask and null are supported (materials/mask.cpp): a mask without its nested bsdf is refused
    // as Mitsuba refuses it, at the mask's line.
    const std::string mask = loadError("<shape type=\"sphere\">\n<bsdf type=\"mask\"/></shape>\n");
    EXPECT_TRUE(has(mask, "<string>:3: mask: no nested bsdf")) << mask;
    EXPECT_EQ(loadError("<shape type=\"sphere\">\n<bsdf type=\"null\"/></shape>\n"), "");
    // Media are supported (media/, integrators/volpath.cpp); one that nothing encloses
    // is refused at its line.
    const std::string medium = loadError("<medium type=\"homogeneous\" id=\"fog\"/>\n");
    EXPECT_TRUE(has(medium, "<string>:2:")) << medium;
    EXPECT_TRUE(has(medium, "has no boundary")) << medium;
}
