// Scene loader: every XML element, value type and transform operation, 0.6 and 3 syntax, includes,
// defaults, paths and refs; and the shared Cornell box / matpreview scenes.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "render/loader/scene_loader.h"
#include "core/xml/xml_parser.h"
#include "core/srgb_transfer.h"
#include "core/xml/xml_values.h"
#include "core/registry.h"
#include "core/source_tree.h"
#include "integrators/path.h"
#include "render/integrator.h"
#include "render/lights/light.h"
#include "render/sensors/perspective.h"
#include "spectral/spectrum_params.h"

namespace fs = std::filesystem;
using namespace iris;

namespace {

fs::path testDir() {
    const fs::path d = fs::temp_directory_path() / ("iris_scene_tests_" + std::to_string(::getpid()));
    fs::create_directories(d);
    return d;
}

std::string writeFile(const std::string& rel, const std::string& contents) {
    const fs::path p = testDir() / rel;
    fs::create_directories(p.parent_path());
    std::ofstream(p, std::ios::binary) << contents;
    return p.string();
}

const char* kTriangleObj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\n";

std::string scene(const std::string& body, const std::string& version = "3.0.0") {
    return "<scene version=\"" + version + "\">\n" + body + "</scene>\n";
}

SceneDescription load(const std::string& name, const std::string& xml, const std::map<std::string, std::string>& defines = {}) {
    return loadScene(writeFile(name, xml), defines);
}

/// Expect loading `xml` (written as `name`) to fail with "name:line:" and every fragment.
void expectLoadError(const std::string& name, const std::string& xml, int line, std::initializer_list<std::string> fragments) {
    const std::string path = writeFile(name, xml);
    try {
        loadScene(path);
        ADD_FAILURE() << name << ": expected an iris::Error";
    } catch (const Error& e) {
        const std::string msg = e.what();
        const std::string where = name + ":" + std::to_string(line) + ":";
        EXPECT_NE(msg.find(where), std::string::npos) << msg << "\n  missing: " << where;
        for (const auto& f : fragments) EXPECT_NE(msg.find(f), std::string::npos) << msg << "\n  missing: " << f;
    }
}

void expectNear(const vec3& a, const vec3& b, float tol = 1e-5f) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

std::string sphereWith(const std::string& transform) {
    return scene("<shape type=\"sphere\"><transform name=\"to_world\">" + transform + "</transform></shape>\n");
}

}  // namespace

TEST(SceneLoader, SensorFilmSamplerIntegrator) {
    const SceneDescription s = load("camera.xml", scene(R"(
<integrator type="direct"><integer name="max_depth" value="3"/><integer name="rr_depth" value="2"/>
  <boolean name="hide_emitters" value="true"/></integrator>
<sensor type="perspective">
  <float name="fov" value="30"/><string name="fov_axis" value="y"/>
  <float name="near_clip" value="0.1"/><float name="far_clip" value="100"/><float name="focus_distance" value="4"/>
  <transform name="to_world"><lookat origin="1, 2, 3" target="1, 2, 4" up="0 1 0"/></transform>
  <sampler type="ldsampler"><integer name="sample_count" value="7"/></sampler>
  <film type="hdrfilm"><integer name="width" value="40"/><integer name="height" value="30"/>
    <string name="pixel_format" value="rgba"/><rfilter type="gaussian"><float name="stddev" value="0.25"/></rfilter></film>
</sensor>
)"));
    ASSERT_TRUE(s.integrator);
    EXPECT_EQ(s.integrator->type(), "direct");
    EXPECT_EQ(s.integrator->maxDepth(), 3);
    const PathParams& pp = dynamic_cast<const PathIntegrator&>(*s.integrator).params();
    EXPECT_EQ(pp.rrDepth, 2);
    EXPECT_TRUE(pp.hideEmitters);
    const auto& persp = dynamic_cast<const PerspectiveSensor&>(*s.camera.sensor);
    EXPECT_FLOAT_EQ(persp.fovDegrees(), 30.0f);
    EXPECT_EQ(persp.fovAxis(), FovAxis::Y);
    EXPECT_EQ(s.camera.width, 40);
    EXPECT_EQ(s.camera.height, 30);
    ASSERT_TRUE(s.camera.filter);
    EXPECT_FLOAT_EQ(s.camera.filter->radius(), 0.75f);  // gaussian truncated at 3 stddev
    EXPECT_GT(s.camera.filter->eval(0.0f), 0.0f);
    EXPECT_EQ(s.spp, 7);
    // lookat: columns are (left, up, dir, origin); looking along +z with up +y gives left = +x.
    const mat4& toWorld = s.camera.sensor->toWorld();
    expectNear(vec3(toWorld[3]), vec3(1, 2, 3));
    expectNear(vec3(toWorld[2]), vec3(0, 0, 1));
    expectNear(vec3(toWorld[1]), vec3(0, 1, 0));
    expectNear(vec3(toWorld[0]), vec3(1, 0, 0));

    const SceneDescription b = load("box.xml", scene(R"(<sensor type="perspective"><film type="hdrfilm"><rfilter type="box"/></film></sensor>)"));
    ASSERT_TRUE(b.camera.filter);
    EXPECT_FLOAT_EQ(b.camera.filter->radius(), 0.5f);
    EXPECT_EQ(b.camera.filter->eval(0.6f), 0.0f);  // a box, not a gaussian
    EXPECT_EQ(b.camera.filter->eval(0.4f), 1.0f);
    EXPECT_EQ(b.camera.width, 768);  // Mitsuba defaults
    EXPECT_EQ(b.integrator->type(), "path");
}

TEST(SceneLoader, TransformsApplyInOrder) {
    auto center = [](const std::string& name, const std::string& t) {
        const SceneDescription s = load(name, sphereWith(t));
        EXPECT_EQ(s.shapes.at(0).type, ShapeDescription::Type::Sphere);
        return std::make_pair(s.shapes[0].center, s.shapes[0].radius);
    };
    // Each operation pre-multiplies: translate then scale moves the centre to 2.
    auto [c1, r1] = center("t1.xml", R"(<translate x="1"/><scale value="2"/>)");
    expectNear(c1, vec3(2, 0, 0));
    EXPECT_FLOAT_EQ(r1, 2.0f);
    auto [c2, r2] = center("t2.xml", R"(<scale value="2"/><translate value="1 0 0"/>)");
    expectNear(c2, vec3(1, 0, 0));
    EXPECT_FLOAT_EQ(r2, 2.0f);
    auto [c3, r3] = center("t3.xml", R"(<translate x="1"/><rotate z="1" angle="90"/>)");
    expectNear(c3, vec3(0, 1, 0));
    auto [c4, r4] = center("t4.xml", R"(<translate x="1"/><rotate value="0, 0, 1" angle="-90"/>)");
    expectNear(c4, vec3(0, -1, 0));
    auto [c5, r5] = center("t5.xml", R"(<matrix value="1 0 0 5  0 1 0 6  0 0 1 7  0 0 0 1"/>)");
    expectNear(c5, vec3(5, 6, 7));
    auto [c6, r6] = center("t6.xml", R"(<scale x="3" y="3" z="3"/><translate y="-1"/>)");
    expectNear(c6, vec3(0, -1, 0));
    EXPECT_FLOAT_EQ(r6, 3.0f);
    expectLoadError("nonuniform.xml", sphereWith(R"(<scale x="2"/>)"), 2, {"sphere", "uniform"});
    expectLoadError("badop.xml", sphereWith(R"(<shear x="2"/>)"), 2, {"unknown transform operation <shear>"});
    expectLoadError("badmatrix.xml", sphereWith(R"(<matrix value="1 2 3"/>)"), 2, {"<matrix> needs 16"});
    expectLoadError("badlookat.xml", sphereWith(R"(<lookat origin="0 0 0" target="0 1 0" up="0 1 0"/>)"), 2, {"lookat", "parallel"});
}

TEST(SceneLoader, BuiltinShapesMeshesMaterialsAndEmitters) {
    writeFile("meshes/tri.obj", kTriangleObj);
    writeFile("meshes/tri.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                                "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
    const SceneDescription s = load("shapes.xml", scene(R"(
<bsdf type="diffuse" id="grey"><rgb name="reflectance" value="0.2, 0.3, 0.4"/></bsdf>
<emitter type="area" id="lamp"><spectrum name="radiance" value="3"/></emitter>
<shape type="rectangle" id="rect">
  <transform name="to_world"><scale value="2"/><translate z="1"/></transform>
  <ref id="grey"/>
  <ref id="lamp"/>
</shape>
<shape type="cube"><ref name="bsdf" id="grey"/><boolean name="flip_normals" value="true"/></shape>
<shape type="disk"><bsdf type="diffuse"/><emitter type="area"><blackbody name="radiance" temperature="5000K" scale="2"/></emitter></shape>
<shape type="obj"><string name="filename" value="meshes/tri.obj"/><boolean name="face_normals" value="true"/></shape>
<shape type="ply"><string name="filename" value="meshes/tri.ply"/>
  <emitter type="area"><spectrum name="radiance" value="400:1, 500:2, 600:3"/></emitter></shape>
<shape type="sphere"><point name="center" x="1" y="2" z="3"/><float name="radius" value="0.5"/>
  <boolean name="flip_normals" value="true"/></shape>
)"));
    ASSERT_EQ(s.shapes.size(), 6u);
    const ShapeDescription& rect = s.shapes[0];
    ASSERT_TRUE(rect.mesh);
    EXPECT_EQ(rect.mesh->triangleCount(), 2u);
    expectNear(rect.mesh->positions[0], vec3(-2, -2, 1));
    expectNear(rect.mesh->positions[2], vec3(2, 2, 1));
    ASSERT_TRUE(rect.material);
    ASSERT_TRUE(rect.emission);
    // A single-valued radiance in a version 3 scene is Mitsuba 3's flat spectrum (version 0.x: × D65;
    // tests/spectral/test_mitsuba_rgb.cpp, SingleValuedEmissionFollowsTheVersion).
    for (float l : {420.0f, 550.0f, 680.0f}) EXPECT_FLOAT_EQ(rect.emission->eval(l), 3.0f);
    EXPECT_EQ(rect.emission->kind(), SpectrumKind::Illuminant);
    EXPECT_EQ(rect.name, "rect");

    const ShapeDescription& cube = s.shapes[1];
    EXPECT_EQ(cube.material, rect.material);  // one material per bsdf id
    EXPECT_EQ(cube.mesh->triangleCount(), 12u);
    // flip_normals: the +x face's normals now point inwards.
    EXPECT_FLOAT_EQ(cube.mesh->normals[0].x, -1.0f);
    EXPECT_FALSE(cube.emission);

    const ShapeDescription& disk = s.shapes[2];
    ASSERT_TRUE(disk.material);
    EXPECT_NE(disk.material, rect.material);
    ASSERT_TRUE(disk.emission);
    EXPECT_GT(disk.emission->eval(580.0f), disk.emission->eval(400.0f));  // 5000 K peaks near 580 nm
    EXPECT_LE(disk.emission->maxValue(), 2.0f + 1e-4f);

    const ShapeDescription& obj = s.shapes[3];
    EXPECT_TRUE(obj.faceNormals);
    EXPECT_TRUE(obj.mesh->normals.empty());
    EXPECT_FALSE(obj.material);  // default material is chosen by the renderer
    EXPECT_NE(obj.name.find("tri.obj"), std::string::npos);

    const ShapeDescription& ply = s.shapes[4];
    EXPECT_EQ(ply.mesh->triangleCount(), 1u);
    EXPECT_NEAR(ply.emission->eval(450.0f), 1.5f, 1e-5f);

    const ShapeDescription& sph = s.shapes[5];
    EXPECT_EQ(sph.type, ShapeDescription::Type::Sphere);
    expectNear(sph.center, vec3(1, 2, 3));
    EXPECT_FLOAT_EQ(sph.radius, 0.5f);
    EXPECT_TRUE(sph.flipNormals);
}

TEST(SceneLoader, SerializedShapes) {
    const std::string mp = sourcePath("../shared/data/scenes/matpreview/matpreview.serialized");
    if (!fs::exists(mp)) GTEST_SKIP() << "shared data not available";
    const SceneDescription s = load("ser.xml", scene("<shape type=\"serialized\"><string name=\"filename\" value=\"" + mp +
                                                     "\"/><integer name=\"shape_index\" value=\"1\"/></shape>\n"));
    ASSERT_EQ(s.shapes.size(), 1u);
    EXPECT_GT(s.shapes[0].mesh->triangleCount(), 100u);
    expectLoadError("serbad.xml", scene("<shape type=\"serialized\">\n<string name=\"filename\" value=\"" + mp +
                                        "\"/><integer name=\"shape_index\" value=\"9\"/></shape>\n"),
                    3, {"matpreview.serialized", "shape_index 9"});
}

TEST(SceneLoader, ValuesAndSpectra) {
    writeFile("spd/flat.spd", "# test\n400 0.5\n700 0.5\n");
    const SceneDescription s = load("values.xml", scene(R"(
<shape type="sphere"><emitter type="area"><spectrum name="radiance" filename="spd/flat.spd"/></emitter></shape>
<shape type="sphere"><emitter type="area"><rgb name="radiance" value="1 1 1"/></emitter></shape>
<shape type="sphere"><emitter type="area"><float name="radiance" value="2.5"/></emitter></shape>
<shape type="sphere"><emitter type="area"><spectrum name="radiance" value="400:1 700:1"/></emitter></shape>
)"));
    ASSERT_EQ(s.shapes.size(), 4u);
    EXPECT_NEAR(s.shapes[0].emission->eval(550.0f), 0.5f, 1e-6f);
    EXPECT_GT(s.shapes[1].emission->eval(550.0f), 0.0f);
    {
        // A float radiance becomes whatever getSpectrum (spectral/spectrum_params.h) makes of a float illuminant.
        Properties ref("emitter", "area", SourceLocation{"ref.xml", 1});
        ref.set("radiance", 2.5f, SourceLocation{"ref.xml", 1});
        const SpectrumPtr expected = getSpectrum(ref, "radiance", SpectrumKind::Illuminant);
        for (float l : {420.0f, 550.0f, 680.0f}) EXPECT_FLOAT_EQ(s.shapes[2].emission->eval(l), expected->eval(l));
    }
    EXPECT_FLOAT_EQ(s.shapes[3].emission->eval(420.0f), 1.0f);
    // Value parsing helpers.
    const SourceLocation at{"x.xml", 1};
    const vec3 c = parseColorValue("#ff8000", true, at);
    EXPECT_FLOAT_EQ(c.x, 1.0f);
    EXPECT_NEAR(c.y, srgbToLinear(128.0f / 255.0f), 1e-6f);
    EXPECT_NEAR(srgbToLinear(0.5f), 0.21404f, 1e-4f);  // IEC 61966-2-1
    EXPECT_FLOAT_EQ(parseColorValue("0.5", false, at).z, 0.5f);
    EXPECT_EQ(camelToSnake("toWorld"), "to_world");
    EXPECT_EQ(camelToSnake("intIOR"), "int_ior");
    EXPECT_EQ(camelToSnake("sampleCount"), "sample_count");
    EXPECT_EQ(camelToSnake("max_depth"), "max_depth");
    EXPECT_THROW(parseFloatValue("1.5x", at), Error);
    EXPECT_THROW(parseIntValue("3.5", at), Error);
    EXPECT_THROW(parseBoolValue("yes", at), Error);
    EXPECT_THROW(parseSpectrumValue("500:1, 400:2", at), Error);
}

TEST(SceneLoader, DefaultsDefinesIncludesAndPaths) {
    writeFile("inc/meshdir/tri.obj", kTriangleObj);
    writeFile("inc/parts/camera.xml", scene(R"(<default name="spp" value="99"/>
<sensor type="perspective"><sampler type="independent"><integer name="sample_count" value="$spp"/></sampler>
<film type="hdrfilm"><integer name="width" value="$res"/><integer name="height" value="$res"/></film></sensor>
)"));
    const std::string main = scene(R"(<default name="spp" value="8"/>
<default name="res" value="16"/>
<path value="meshdir"/>
<include filename="parts/camera.xml"/>
<shape type="obj"><string name="filename" value="tri.obj"/></shape>
)");
    const SceneDescription s = load("inc/main.xml", main);
    EXPECT_EQ(s.spp, 8);  // the first default wins
    EXPECT_EQ(s.camera.width, 16);
    ASSERT_EQ(s.shapes.size(), 1u);
    const SceneDescription d = load("inc/main.xml", main, {{"spp", "3"}, {"res", "5"}});
    EXPECT_EQ(d.spp, 3);
    EXPECT_EQ(d.camera.height, 5);
    // loadSceneFromString resolves against baseDir.
    const SceneDescription fromString = loadSceneFromString(main, (testDir() / "inc").string());
    EXPECT_EQ(fromString.shapes.size(), 1u);
    try {
        loadSceneFromString(scene("<bogus/>\n"), ".");
        ADD_FAILURE();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("<string>:2:"), std::string::npos) << e.what();
    }
}

TEST(SceneLoader, ObjectsKnowTheFormatVersionOfTheirFile) {
    // Version-dependent plugin semantics (docs/scene_format.md) read Properties::formatVersion().
    const ParsedScene s06 = parseSceneString("<scene version=\"0.6.0\"><bsdf type=\"diffuse\" id=\"a\"/></scene>", ".");
    const ParsedScene s21 = parseSceneString("<scene version=\"2.1.0\"><bsdf type=\"diffuse\" id=\"a\"/></scene>", ".");
    ASSERT_EQ(s06.objects.size(), 1u);
    ASSERT_EQ(s21.objects.size(), 1u);
    EXPECT_EQ(s06.objects[0]->formatVersion(), 0);
    EXPECT_EQ(s21.objects[0]->formatVersion(), 2);
    EXPECT_EQ(Properties().formatVersion(), 3);  // objects built in code: Mitsuba 3
}

TEST(SceneLoader, Mitsuba06Syntax) {
    writeFile("old/tri.obj", kTriangleObj);
    const SceneDescription s = load("old/scene06.xml", scene(R"(
<integrator type="path"><integer name="maxDepth" value="4"/><integer name="rrDepth" value="3"/></integrator>
<sensor type="perspective"><float name="fov" value="40"/><string name="fovAxis" value="smaller"/>
  <transform name="toWorld"><lookAt origin="0 0 -5" target="0 0 0" up="0 1 0"/></transform>
  <sampler type="independent"><integer name="sampleCount" value="12"/></sampler>
  <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="6"/><string name="pixelFormat" value="rgb"/></film>
</sensor>
<shape type="sphere"><transform name="toWorld"><translate x="2"/></transform>
  <bsdf type="diffuse"><srgb name="reflectance" value="#808080"/></bsdf></shape>
<shape type="obj"><string name="filename" value="tri.obj"/><boolean name="flipTexCoords" value="false"/></shape>
)", "0.6.0"));
    EXPECT_EQ(s.integrator->maxDepth(), 4);
    EXPECT_EQ(dynamic_cast<const PathIntegrator&>(*s.integrator).params().rrDepth, 3);
    EXPECT_EQ(s.spp, 12);
    EXPECT_EQ(dynamic_cast<const PerspectiveSensor&>(*s.camera.sensor).fovAxis(), FovAxis::Smaller);
    expectNear(vec3(s.camera.sensor->toWorld()[3]), vec3(0, 0, -5));
    expectNear(s.shapes.at(0).center, vec3(2, 0, 0));
    EXPECT_TRUE(s.shapes[0].material);
    // intIOR → int_ior reaches the material factory (diffuse does not know it).
    expectLoadError("old/ior06.xml", scene("<bsdf type=\"diffuse\">\n<float name=\"intIOR\" value=\"1.5\"/></bsdf>\n", "0.6.0"), 3,
                    {"unknown parameter 'int_ior'"});
    // In 3.x syntax, camelCase is not translated.
    expectLoadError("old/camel3.xml", scene("<shape type=\"sphere\">\n<transform name=\"toWorld\"/></shape>\n"), 3,
                    {"unknown parameter 'toWorld'"});
}

TEST(SceneLoader, TopLevelLights) {
    if (!LightRegistry::instance().has("point") || !LightRegistry::instance().has("constant")) GTEST_SKIP() << "lights not registered";
    const SceneDescription s = load("lights.xml", scene(R"(
<emitter type="point"><point name="position" x="0" y="1" z="0"/><rgb name="intensity" value="5"/></emitter>
<emitter type="constant"><spectrum name="radiance" value="0.1"/></emitter>
)"));
    EXPECT_EQ(s.lights.size(), 2u);
    expectLoadError("badlight.xml", scene("\n<emitter type=\"laser\"/>\n"), 3, {"emitter type 'laser'", "point"});
    expectLoadError("lightparam.xml", scene("<emitter type=\"point\">\n<float name=\"wattage\" value=\"3\"/></emitter>\n"), 3,
                    {"unknown parameter 'wattage'"});
}

TEST(SceneLoader, ErrorsNameFileLineAndProblem) {
    expectLoadError("e_bsdf.xml", scene("<shape type=\"sphere\">\n  <bsdf type=\"plasticky\"/>\n</shape>\n"), 3,
                    {"unknown bsdf type 'plasticky'", "supported:", "diffuse"});
    expectLoadError("e_ref.xml", scene("<shape type=\"sphere\">\n  <ref id=\"nothing\"/>\n</shape>\n"), 3, {"unknown id 'nothing'"});
    expectLoadError("e_dup.xml", scene("<bsdf type=\"diffuse\" id=\"a\"/>\n<bsdf type=\"diffuse\" id=\"a\"/>\n"), 3,
                    {"duplicate id 'a'", "e_dup.xml:2"});
    expectLoadError("e_param.xml", scene("<sensor type=\"perspective\">\n<float name=\"fov\" value=\"$fov\"/></sensor>\n"), 3,
                    {"undefined parameter '$fov'"});
    expectLoadError("e_unknown.xml", scene("<bsdf type=\"diffuse\">\n<rgb name=\"reflectance\" value=\"0.5\"/>\n"
                                           "<float name=\"roughness\" value=\"0.1\"/></bsdf>\n"),
                    4, {"unknown parameter 'roughness'", "bsdf 'diffuse'"});
    expectLoadError("e_rfilter.xml", scene("<sensor type=\"perspective\"><film type=\"hdrfilm\">\n<rfilter type=\"sinc\"/></film></sensor>\n"), 3,
                    {"unknown rfilter type 'sinc' (supported: ", "box, ", "gaussian"});
    expectLoadError("e_integrator.xml", scene("\n<integrator type=\"bdpt\"/>\n"), 3,
                    {"unknown integrator type 'bdpt' (supported: ", "direct, ", "path"});
    expectLoadError("e_shape.xml", scene("\n<shape type=\"torus\"/>\n"), 3,
                    {"unknown shape type 'torus' (supported: ", "cube, ", "sphere"});
    expectLoadError("e_sensor.xml", scene("\n<sensor type=\"fisheye\"/>\n"), 3,
                    {"unknown sensor type 'fisheye' (supported: ", "perspective"});
    expectLoadError("e_filmtype.xml", scene("<sensor type=\"perspective\">\n<film type=\"specfilm\"/></sensor>\n"), 3,
                    {"unknown film type 'specfilm' (supported: ", "hdrfilm"});
    expectLoadError("e_sampler.xml", scene("<sensor type=\"perspective\">\n<sampler type=\"magic\"/></sensor>\n"), 3,
                    {"unknown sampler type 'magic' (supported: ", "independent"});
    expectLoadError("e_file.xml", scene("<shape type=\"obj\">\n<string name=\"filename\" value=\"missing.obj\"/></shape>\n"), 3,
                    {"file 'missing.obj' not found"});
    expectLoadError("e_syntax.xml", scene("<shape type=\"sphere\">\n<float name=\"radius\" value=\"1\">\n</shape>\n"), 4,
                    {"XML parse error"});
    expectLoadError("e_element.xml", scene("\n<frobnicate/>\n"), 3, {"unknown element <frobnicate>"});
    expectLoadError("e_number.xml", scene("<shape type=\"sphere\">\n<float name=\"radius\" value=\"one\"/></shape>\n"), 3,
                    {"'one' is not a valid number"});
    expectLoadError("e_type.xml", scene("<shape type=\"sphere\">\n<string name=\"radius\" value=\"1\"/></shape>\n"), 3,
                    {"parameter 'radius'", "must be a float"});
    expectLoadError("e_area.xml", scene("\n<emitter type=\"area\"><rgb name=\"radiance\" value=\"1\"/></emitter>\n"), 3,
                    {"area emitter must be inside a <shape>"});
    expectLoadError("e_film.xml", scene("<sensor type=\"perspective\">\n<film type=\"hdrfilm\"><integer name=\"width\" value=\"100000000\"/></film></sensor>\n"),
                    3, {"film size", "out of range"});
    expectLoadError("e_attr.xml", scene("<shape type=\"sphere\">\n<float name=\"radius\" valeu=\"1\"/></shape>\n"), 3,
                    {"unexpected attribute 'valeu'"});
    expectLoadError("e_root.xml", "<scen version=\"3.0.0\"/>\n", 1, {"root element must be <scene>"});
    expectLoadError("e_version.xml", "<scene>\n</scene>\n", 1, {"version"});
    expectLoadError("e_twice.xml", scene("<shape type=\"sphere\"><float name=\"radius\" value=\"1\"/>\n<float name=\"radius\" value=\"2\"/></shape>\n"),
                    3, {"'radius' is specified twice"});
    expectLoadError("e_emitter.xml", scene("<shape type=\"sphere\">\n<emitter type=\"point\"/></shape>\n"), 3,
                    {"cannot be attached to a shape"});
    expectLoadError("e_nested.xml", scene("<shape type=\"sphere\"><bsdf type=\"diffuse\">\n<rgb name=\"reflectance\" value=\"1 2\"/></bsdf></shape>\n"),
                    3, {"colour needs 1 or 3 values"});
    expectLoadError("e_sampler.xml", scene("\n<sampler type=\"independent\"/>\n"), 3, {"must be inside a <sensor>"});
    expectLoadError("e_spp.xml", scene("<sensor type=\"perspective\"><sampler type=\"independent\">\n<integer name=\"sample_count\" value=\"0\"/></sampler></sensor>\n"),
                    3, {"sample_count"});
    // Errors inside an included file name that file and its line.
    writeFile("e_inc_part.xml", scene("\n\n<shape type=\"cone\"/>\n"));
    writeFile("e_inc_main.xml", scene("<include filename=\"e_inc_part.xml\"/>\n"));
    expectLoadError("e_inc_part.xml", scene("\n\n<shape type=\"cone\"/>\n"), 4, {"shape type 'cone'"});
    EXPECT_THROW(loadScene((testDir() / "e_inc_main.xml").string()), Error);
    // Recursive includes: reported at the include that closes the cycle.
    writeFile("e_rec_b.xml", scene("<include filename=\"e_rec_a.xml\"/>\n"));
    writeFile("e_rec_a.xml", scene("<include filename=\"e_rec_b.xml\"/>\n"));
    try {
        loadScene((testDir() / "e_rec_a.xml").string());
        ADD_FAILURE();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("e_rec_b.xml:2: recursive include"), std::string::npos) << e.what();
    }
    // Circular references.
    expectLoadError("e_cycle.xml", scene("<bsdf type=\"twosided\" id=\"a\">\n<ref id=\"a\"/></bsdf>\n"), 3, {"circular reference to 'a'"});
    // Forward references are allowed (as in Mitsuba).
    const SceneDescription fwd = load("fwd.xml", scene("<shape type=\"sphere\"><ref id=\"later\"/></shape>\n<bsdf type=\"diffuse\" id=\"later\"/>\n"));
    EXPECT_TRUE(fwd.shapes.at(0).material);
    // Missing scene file.
    try {
        loadScene((testDir() / "nope.xml").string());
        ADD_FAILURE();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("nope.xml"), std::string::npos);
    }
}

namespace {
std::string cboxPath(const std::string& name) { return sourcePath("../shared/data/scenes/cbox/" + name); }
}  // namespace

TEST(SceneLoader, CornellBoxScenes) {
    for (const char* name : {"cbox-rgb.xml", "cbox-spectral.xml"}) {
        const std::string path = cboxPath(name);
        if (!fs::exists(path)) GTEST_SKIP() << "shared data not available";
        const SceneDescription s = loadScene(path);
        SCOPED_TRACE(name);
        ASSERT_EQ(s.shapes.size(), 8u);
        EXPECT_EQ(s.spp, 256);
        EXPECT_EQ(s.camera.width, 256);
        EXPECT_EQ(s.camera.height, 256);
        const auto& persp = dynamic_cast<const PerspectiveSensor&>(*s.camera.sensor);
        EXPECT_NEAR(persp.fovDegrees(), 39.3077f, 1e-4f);
        EXPECT_EQ(persp.fovAxis(), FovAxis::Smaller);
        EXPECT_EQ(s.camera.filter->eval(0.4f), 1.0f);  // box
        expectNear(vec3(persp.toWorld()[3]), vec3(278, 273, -800), 1e-3f);
        expectNear(vec3(persp.toWorld()[2]), vec3(0, 0, 1));
        EXPECT_EQ(s.integrator->type(), "path");
        EXPECT_EQ(s.integrator->maxDepth(), 6);
        EXPECT_TRUE(s.lights.empty());
        int emitters = 0;
        for (const ShapeDescription& sh : s.shapes) {
            ASSERT_TRUE(sh.material) << sh.name;
            EXPECT_EQ(sh.type, ShapeDescription::Type::Mesh);
            emitters += sh.emission ? 1 : 0;
        }
        EXPECT_EQ(emitters, 1);
        ASSERT_TRUE(s.shapes[0].emission);  // the luminaire, moved down by 0.5
        EXPECT_NEAR(s.shapes[0].mesh->positions[0].y, 548.3f, 1e-3f);
        EXPECT_GT(s.shapes[0].emission->eval(650.0f), s.shapes[0].emission->eval(450.0f));
        // The floor, walls and ceiling share the "white" material; the two boxes share "box".
        EXPECT_EQ(s.shapes[1].material, s.shapes[2].material);
        EXPECT_EQ(s.shapes[6].material, s.shapes[7].material);
        EXPECT_NE(s.shapes[1].material, s.shapes[4].material);
        // -D overrides the file's defaults.
        const SceneDescription d = loadScene(path, {{"spp", "4"}, {"res", "32"}});
        EXPECT_EQ(d.spp, 4);
        EXPECT_EQ(d.camera.width, 32);
    }
}

TEST(SceneLoader, MatpreviewLoadsOrFailsCleanly) {
    const std::string path = sourcePath("../shared/data/scenes/matpreview/matpreview.xml");
    if (!fs::exists(path)) GTEST_SKIP() << "shared data not available";
    if (MaterialRegistry::instance().has("plastic") && LightRegistry::instance().has("envmap")) {
        const SceneDescription s = loadScene(path);
        EXPECT_EQ(s.shapes.size(), 3u);
        EXPECT_EQ(s.lights.size(), 1u);
        EXPECT_EQ(s.camera.width, 683);
        EXPECT_EQ(s.spp, 64);
    } else {
        try {
            loadScene(path);
            ADD_FAILURE() << "matpreview needs plastic and envmap";
        } catch (const Error& e) {
            const std::string msg = e.what();
            EXPECT_NE(msg.find("matpreview.xml:"), std::string::npos) << msg;
            EXPECT_NE(msg.find("not supported yet"), std::string::npos) << msg;
        }
    }
}

namespace {
/// A test-local material that records what the loader handed to its factory.
struct ProbeRecord {
    std::string intIor;
    std::vector<std::string> childIds, childTags;
    std::string texType;
    int intIorLine = 0;
    int calls = 0;
};
ProbeRecord gProbe;

class ProbeMaterial final : public Material {
public:
    const BSDF* getBSDF(const ShadingPoint&, SampledWavelengths&, Arena&) const override { return nullptr; }
};

std::shared_ptr<Material> createProbe(const Properties& p) {
    ++gProbe.calls;
    gProbe.intIor = p.getString("int_ior");
    gProbe.intIorLine = p.locationOf("int_ior").line;
    gProbe.childIds.clear();
    gProbe.childTags.clear();
    for (const PropertiesPtr& c : p.children()) {
        gProbe.childIds.push_back(c->id());
        gProbe.childTags.push_back(c->tag() + ":" + c->type());
    }
    const PropertiesPtr tex = p.getObject("tex");
    gProbe.texType = tex->tag() + ":" + tex->type();
    return std::make_shared<ProbeMaterial>();
}
IRIS_REGISTER(MaterialRegistry, "loader_test_probe", createProbe);
}  // namespace

TEST(SceneLoader, ParametersChildrenAndRefsReachTheFactory) {
    gProbe = ProbeRecord{};
    const SceneDescription s = load("probe.xml", scene(R"(<bsdf type="loader_test_probe" id="probe">
  <string name="int_ior" value="water"/>
  <bsdf type="diffuse" id="inline"/>
  <ref id="inner"/>
  <texture type="checkerboard" name="tex"/>
</bsdf>
<bsdf type="diffuse" id="inner"/>
<shape type="sphere"><ref id="probe"/></shape>
<shape type="sphere"><ref name="bsdf" id="probe"/></shape>
)"));
    EXPECT_EQ(gProbe.calls, 1);  // created once, shared by both shapes
    EXPECT_EQ(gProbe.intIor, "water");  // named presets pass through as strings
    EXPECT_EQ(gProbe.intIorLine, 3);
    EXPECT_EQ(gProbe.childIds, (std::vector<std::string>{"inline", "inner"}));
    EXPECT_EQ(gProbe.childTags, (std::vector<std::string>{"bsdf:diffuse", "bsdf:diffuse"}));
    EXPECT_EQ(gProbe.texType, "texture:checkerboard");
    ASSERT_EQ(s.shapes.size(), 2u);
    EXPECT_EQ(s.shapes[0].material, s.shapes[1].material);
    // The same id used twice in one shape is an error (two bsdfs).
    expectLoadError("probe2.xml", scene("<bsdf type=\"diffuse\" id=\"d\"/>\n<shape type=\"sphere\"><ref id=\"d\"/>\n<ref name=\"bsdf\" id=\"d\"/></shape>\n"),
                    3, {"more than one bsdf"});
}
