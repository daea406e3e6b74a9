// Sensor plugins: Mitsuba's default field of view (a 50 mm lens on 36 × 24 mm film, measured along
// the diagonal), focal_length / focalLength, fov with fov_axis, and their errors.
#include <gtest/gtest.h>

#include "render/loader/scene_loader.h"
#include "render/sensors/perspective.h"

using namespace iris;

namespace {

SceneDescription loadSensor(const std::string& sensorBody, int w, int h, const std::string& version = "3.0.0") {
    const std::string xml = "<scene version=\"" + version + "\"><sensor type=\"perspective\">" + sensorBody +
                            "<film type=\"hdrfilm\"><integer name=\"width\" value=\"" + std::to_string(w) +
                            "\"/><integer name=\"height\" value=\"" + std::to_string(h) + "\"/></film></sensor></scene>";
    return loadSceneFromString(xml, ".");
}

/// Full angle in degrees between the rays through the left and right edges at mid-height.
double horizontalFovDegrees(const SceneDescription& s) {
    const Sensor& cam = *s.camera.sensor;
    const float y = 0.5f * s.camera.height;
    const vec3 a = cam.generateRay(vec2(0.0f, y)).d, b = cam.generateRay(vec2(float(s.camera.width), y)).d;
    return std::acos(std::clamp(double(glm::dot(a, b)), -1.0, 1.0)) * 180.0 / M_PI;
}

double diagonalFovDegrees(const SceneDescription& s) {
    const Sensor& cam = *s.camera.sensor;
    const vec3 a = cam.generateRay(vec2(0.0f)).d, b = cam.generateRay(vec2(float(s.camera.width), float(s.camera.height))).d;
    return std::acos(std::clamp(double(glm::dot(a, b)), -1.0, 1.0)) * 180.0 / M_PI;
}

}  // namespace

TEST(Sensors, DefaultFovIsA50mmLensAlongTheDiagonal) {
    // 2 atan(√(36² + 24²) / 100) = 46.793° along the diagonal whatever the aspect ratio; 34.0° across
    // a square image (iris used 39.6° across x before: this fails then).
    EXPECT_NEAR(diagonalFovDegrees(loadSensor("", 64, 64)), 46.793, 1e-2);
    EXPECT_NEAR(horizontalFovDegrees(loadSensor("", 64, 64)), 34.0, 0.05);
    EXPECT_NEAR(diagonalFovDegrees(loadSensor("", 96, 64)), 46.793, 1e-2);
    // 35 mm lens: 2 atan(43.267 / 70) = 63.44°.
    EXPECT_NEAR(diagonalFovDegrees(loadSensor(R"(<string name="focal_length" value="35mm"/>)", 80, 40)), 63.44, 1e-2);
    EXPECT_NEAR(diagonalFovDegrees(loadSensor(R"(<string name="focalLength" value="35mm"/>)", 80, 40, "0.6.0")), 63.44, 1e-2);
}

TEST(Sensors, FovAppliesToFovAxis) {
    EXPECT_NEAR(horizontalFovDegrees(loadSensor(R"(<float name="fov" value="60"/>)", 80, 40)), 60.0, 1e-2);
    const SceneDescription y = loadSensor(R"(<float name="fov" value="30"/><string name="fov_axis" value="y"/>)", 80, 40);
    // tan(hx) = 2 tan(15°).
    EXPECT_NEAR(horizontalFovDegrees(y), 2.0 * std::atan(2.0 * std::tan(15.0 * M_PI / 180.0)) * 180.0 / M_PI, 1e-2);
}

TEST(Sensors, BadFocalLengthAndBothFovAndFocalLengthAreErrors) {
    EXPECT_THROW(loadSensor(R"(<string name="focal_length" value="wide"/>)", 8, 8), Error);
    EXPECT_THROW(loadSensor(R"(<string name="focal_length" value="-5mm"/>)", 8, 8), Error);
    EXPECT_THROW(loadSensor(R"(<float name="fov" value="40"/><string name="focal_length" value="50mm"/>)", 8, 8), Error);
}

TEST(Sensors, OrthographicFollowsMitsubasToWorldScale) {
    // to_world = scale 2: the film spans x ∈ [−2, 2], y ∈ [−1, 1] (aspect 2) at z = 2 · near_clip.
    const SceneDescription s = loadSceneFromString(R"(<scene version="3.0.0"><sensor type="orthographic">
        <transform name="to_world"><scale value="2"/><translate z="-10"/></transform>
        <film type="hdrfilm"><integer name="width" value="80"/><integer name="height" value="40"/></film></sensor></scene>)", ".");
    const Sensor& cam = *s.camera.sensor;
    const Ray centre = cam.generateRay(vec2(40.0f, 20.0f)), corner = cam.generateRay(vec2(0.0f, 0.0f));
    EXPECT_NEAR(centre.d.z, 1.0f, 1e-6f);
    EXPECT_EQ(centre.d, corner.d);  // parallel rays
    EXPECT_NEAR(centre.o.x, 0.0f, 1e-5f);
    EXPECT_NEAR(centre.o.z, -10.0f + 0.02f, 1e-5f);
    // Image top-left is camera +x (left), +y (up).
    EXPECT_NEAR(corner.o.x, 2.0f, 1e-5f);
    EXPECT_NEAR(corner.o.y, 1.0f, 1e-5f);
    const std::string bad = R"(<scene version="3.0.0"><sensor type="orthographic"><float name="near_clip" value="5"/><float name="far_clip" value="1"/></sensor></scene>)";
    EXPECT_THROW(loadSceneFromString(bad, "."), Error);
}
