#include "tests/support/light_tracing_scenes.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <vector>

#include <gtest/gtest.h>

#include "core/io/image.h"
#include "render/loader/scene_loader.h"
#include "render/renderer.h"
#include "render/scene.h"

namespace iris::test {

std::string perspectiveSensor(const std::string& rfilter) {
    return R"(<sensor type="perspective"><float name="fov" value="45"/>
        <transform name="to_world"><lookat origin="0, 1.2, 4.5" target="0, 0.8, 0" up="0, 1, 0"/></transform>
        <film type="hdrfilm"><integer name="width" value="$res"/><integer name="height" value="$res"/>)" +
           rfilter + R"(</film></sensor>)";
}

std::string lightTracingScene(const std::string& light, const std::string& extraShapes, const std::string& sensor) {
    return R"(<scene version="3.0.0">
    <default name="integrator" value="path"/>
    <default name="max_depth" value="3"/>
    <default name="res" value="16"/>
    <integrator type="$integrator"><integer name="max_depth" value="$max_depth"/></integrator>
    )" + (sensor.empty() ? perspectiveSensor() : sensor) + R"(
    <shape type="rectangle"><transform name="to_world"><rotate x="1" angle="-90"/><scale value="3"/></transform>
        <bsdf type="diffuse"><rgb name="reflectance" value="0.7, 0.6, 0.5"/></bsdf></shape>
    <shape type="rectangle"><transform name="to_world"><scale value="3"/><translate z="-1.5"/></transform>
        <bsdf type="diffuse"><rgb name="reflectance" value="0.3, 0.6, 0.3"/></bsdf></shape>
    <shape type="sphere"><point name="center" x="0.3" y="0.6" z="0"/><float name="radius" value="0.6"/>
        <bsdf type="diffuse"><rgb name="reflectance" value="0.8, 0.3, 0.3"/></bsdf></shape>
    )" + extraShapes + "\n    " + light + "\n</scene>\n";
}

std::map<std::string, std::string> testLights() {
    const std::string dir = lightTracingDataDir();
    return {
        {"point", R"(<emitter type="point"><point name="position" x="-0.5" y="2.2" z="0.8"/><rgb name="intensity" value="4"/></emitter>)"},
        {"spot", R"(<emitter type="spot"><rgb name="intensity" value="8"/><float name="cutoff_angle" value="35"/>
            <transform name="to_world"><lookat origin="-0.5, 2.5, 1" target="0.2, 0, 0"/></transform></emitter>)"},
        {"directional", R"(<emitter type="directional"><vector name="direction" x="0.3" y="-1" z="-0.4"/><rgb name="irradiance" value="1.5"/></emitter>)"},
        {"projector", R"(<emitter type="projector"><float name="fov" value="40"/><float name="scale" value="3"/>
            <texture type="checkerboard" name="irradiance"><rgb name="color0" value="0.2"/><rgb name="color1" value="1"/></texture>
            <transform name="to_world"><lookat origin="-0.8, 2.5, 1.5" target="0.2, 0.3, 0"/></transform></emitter>)"},
        {"constant", R"(<emitter type="constant"><rgb name="radiance" value="0.6, 0.7, 0.9"/></emitter>)"},
        {"envmap", "<emitter type=\"envmap\"><string name=\"filename\" value=\"" + dir + "/env.exr\"/></emitter>"},
        {"area_rectangle", R"(<shape type="rectangle"><transform name="to_world"><rotate x="1" angle="90"/><scale value="0.4"/><translate y="2.4"/></transform>
            <emitter type="area"><rgb name="radiance" value="8"/></emitter></shape>)"},
        {"area_sphere", R"(<shape type="sphere"><point name="center" x="-0.8" y="1.9" z="0.6"/><float name="radius" value="0.25"/>
            <emitter type="area"><rgb name="radiance" value="6, 5, 4"/></emitter></shape>)"},
        {"area_textured", R"(<shape type="rectangle"><transform name="to_world"><rotate x="1" angle="90"/><scale value="0.5"/><translate y="2.4"/></transform>
            <emitter type="area"><texture type="checkerboard" name="radiance"><rgb name="color0" value="2"/><rgb name="color1" value="12, 8, 4"/></texture></emitter></shape>)"},
    };
}

namespace {

/// An icosahedron (20 triangles) with the normals of a sphere at its vertices: smooth shading
/// normals up to 37° from the geometric ones.
void writeIcosphere(const std::string& path) {
    const float t = (1.0f + std::sqrt(5.0f)) / 2.0f;
    std::vector<vec3> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                           {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    std::vector<ivec3> f = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                            {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
                            {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
    for (vec3& p : v) p = glm::normalize(p);
    const std::vector<ivec3>& g = f;
    std::ofstream out(path);
    for (const vec3& p : v) out << "v " << p.x << " " << p.y << " " << p.z << "\n";
    for (const vec3& p : v) out << "vn " << p.x << " " << p.y << " " << p.z << "\n";
    for (const ivec3& tri : g)
        out << "f " << tri[0] + 1 << "//" << tri[0] + 1 << " " << tri[1] + 1 << "//" << tri[1] + 1 << " " << tri[2] + 1 << "//" << tri[2] + 1 << "\n";
}

void writeEnvironment(const std::string& path) {
    Image img(8, 4, 3);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 8; ++x) {
            img.at(x, y, 0) = 0.2f + 0.3f * float(x) / 7;
            img.at(x, y, 1) = 0.3f + 0.4f * float(3 - y) / 3;
            img.at(x, y, 2) = y == 0 && x == 2 ? 6.0f : 0.5f;
        }
    writeEXR(path, img);
}

}  // namespace

const std::string& lightTracingDataDir() {
    static const std::string dir = [] {
        const std::string d = ::testing::TempDir() + "iris_light_tracing";
        std::filesystem::create_directories(d);
        writeEnvironment(d + "/env.exr");
        writeIcosphere(d + "/icosphere.obj");
        return d;
    }();
    return dir;
}

Film renderLightTracingScene(const std::string& xml, const RenderSpec& spec) {
    SceneDescription desc = loadSceneFromString(xml, ".", spec.defines);
    if (spec.edit) spec.edit(desc);
    const Scene scene(std::move(desc));
    RenderOptions opt;
    opt.spp = spec.spp;
    opt.seed = spec.seed;
    opt.rgbMode = spec.rgb;
    opt.threads = spec.threads;
    opt.spectralSamples = spec.spectralSamples;
    Film film(scene.description().camera.width, scene.description().camera.height);
    Renderer(scene, opt).render(film);
    return film;
}

}  // namespace iris::test
