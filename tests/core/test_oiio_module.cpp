// The OpenImageIO module (libiris_oiio.so, loaded on demand): a PNG texture and JPEG output work
// through it in the `render` executable, EXR-only runs and the PNG beside the EXR (iris's own
// encoder) never need it, and a missing or broken
// module ($IRIS_OIIO_MODULE) gives one clear error line naming the image file, not a crash.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include <unistd.h>

#include "tests/support/app_runner.h"
#include "core/io/image.h"
#include "core/io/oiio_loader.h"
#include "core/srgb_transfer.h"
#include "core/xml/xml_values.h"
#include "materials/textures/bitmap.h"
#include "tests/support/mapped_libraries.h"

using namespace iris;
using namespace iris::testing;

namespace {

using test::lineCount;
using test::mappedLibrary;

std::string tempPath(const std::string& name) { return iris::testing::tempPath("iris_oiio", name); }

/// A small scene lit by a constant emitter whose sphere has a bitmap texture from `texture`.
std::string texturedScene(const std::string& texture) {
    return R"(<scene version="3.0.0">
    <integrator type="path"/>
    <sensor type="perspective">
        <float name="fov" value="40"/>
        <transform name="to_world"><lookat origin="0, 0, -4" target="0, 0, 0" up="0, 1, 0"/></transform>
        <sampler type="independent"><integer name="sample_count" value="2"/></sampler>
        <film type="hdrfilm"><integer name="width" value="16"/><integer name="height" value="12"/></film>
    </sensor>
    <shape type="sphere"><bsdf type="diffuse"><texture type="bitmap" name="reflectance">
        <string name="filename" value=")" +
           texture + R"("/></texture></bsdf></shape>
    <emitter type="constant"><float name="radiance" value="1"/></emitter>
</scene>
)";
}

/// A 4x2 PNG with distinct 8-bit values.
std::string writeTexturePng(const std::string& name) {
    Image img(4, 2, 3);
    for (size_t i = 0; i < img.pixels.size(); ++i) img.pixels[i] = float((i * 37) % 256) / 255.0f;
    const std::string p = tempPath(name);
    writeLDR(p, img);
    return p;
}

}  // namespace

TEST(OiioModule, PngTextureIsDecodedFromSrgbLikeTheStoredCodes) {
    const std::string png = writeTexturePng("tex.png");
    const auto decoded = Bitmap::loadUncached(png, false), raw = Bitmap::loadUncached(png, true);
    ASSERT_EQ(decoded->width(), 4);
    ASSERT_EQ(decoded->channels(), 3);
    for (size_t i = 0; i < 4 * 2 * 3; ++i) {
        // The stored 8-bit code comes back as code/255 (to float rounding), decoded from sRGB
        // exactly as srgbToLinear does.
        const float stored = raw->image().pixels[i];
        EXPECT_EQ(std::lround(stored * 255.0f), long((i * 37) % 256)) << i;
        EXPECT_NEAR(stored, float((i * 37) % 256) / 255.0f, 1e-6f) << i;
        EXPECT_EQ(decoded->image().pixels[i], srgbToLinear(stored)) << i;
    }
    std::filesystem::remove(png);
}

TEST(OiioModule, RenderWithPngTextureAndPngOutput) {
    const std::string png = writeTexturePng("render_tex.png");
    const std::string scene = tempPath("textured.xml"), out = tempPath("textured.exr");
    writeTextFile(scene, texturedScene(png));
    const RunResult r = runCommand(appPath("render") + " " + scene + " -o " + out + " --quiet --threads 1");
    ASSERT_EQ(r.exitCode, 0) << r.stderrText;
    const std::string outPng = std::filesystem::path(out).replace_extension(".png").string();
    const Image exr = readImage(out), ldr = readImage(outPng);
    EXPECT_EQ(exr.width, 16);
    EXPECT_EQ(ldr.width, 16);
    EXPECT_EQ(ldr.height, 12);
    float maxCode = 0.0f;
    for (float v : ldr.pixels) maxCode = std::max(maxCode, v);
    EXPECT_GT(maxCode, 0.0f);  // the lit, textured sphere is visible
    // -o x.png: only the PNG.
    const std::string only = tempPath("only.png");
    const RunResult r2 = runCommand(appPath("render") + " " + scene + " -o " + only + " --quiet --threads 1");
    ASSERT_EQ(r2.exitCode, 0) << r2.stderrText;
    EXPECT_EQ(readImage(only).width, 16);
    for (const std::string& p : {png, scene, out, outPng, only}) std::filesystem::remove(p);
}

TEST(OiioModule, MissingModuleGivesAClearErrorNamingTheFile) {
    const std::string out = tempPath("plain.exr");
    // A scene without images, rendered to EXR only, never needs the module.
    const std::string plain = tempPath("no_texture.xml");
    writeTextFile(plain, R"(<scene version="3.0.0">
    <sensor type="perspective"><film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/></film>
        <sampler type="independent"><integer name="sample_count" value="1"/></sampler></sensor>
    <shape type="sphere"><bsdf type="diffuse"/></shape>
    <emitter type="constant"/>
</scene>
)");
    const std::string missing = "/nonexistent/libiris_oiio.so";
    const std::string env = std::string(kOiioModuleEnv) + "=" + missing + " ";
    RunResult r = runCommand(env + appPath("render") + " " + plain + " -o " + out + " --quiet --no-png");
    EXPECT_EQ(r.exitCode, 0) << r.stderrText;
    EXPECT_TRUE(std::filesystem::exists(out));

    // Nor do EXR inputs (read with OpenEXR): an EXR environment map and an EXR bitmap texture.
    Image envImg(8, 4, 3);
    for (size_t i = 0; i < envImg.pixels.size(); ++i) envImg.pixels[i] = 0.5f + float(i % 5) * 0.25f;
    const std::string envExr = tempPath("env.exr");
    writeEXR(envExr, envImg);
    const std::string exrScene = tempPath("exr_inputs.xml");
    std::string xml = texturedScene(envExr);
    const std::string constant = R"(<emitter type="constant"><float name="radiance" value="1"/></emitter>)";
    xml.replace(xml.find(constant), constant.size(), "<emitter type=\"envmap\"><string name=\"filename\" value=\"" + envExr + "\"/></emitter>");
    writeTextFile(exrScene, xml);
    r = runCommand(env + appPath("render") + " " + exrScene + " -o " + out + " --quiet --no-png");
    EXPECT_EQ(r.exitCode, 0) << r.stderrText;

    // The PNG beside the EXR does not need it (core/io/png_writer.h); a JPEG output does: one
    // error line naming the JPEG and the module.
    const std::string outPng = std::filesystem::path(out).replace_extension(".png").string();
    r = runCommand(env + appPath("render") + " " + plain + " -o " + out + " --quiet");
    EXPECT_EQ(r.exitCode, 0) << r.stderrText;
    EXPECT_TRUE(std::filesystem::exists(outPng));
    const std::string outJpg = tempPath("plain.jpg");
    r = runCommand(env + appPath("render") + " " + plain + " -o " + outJpg + " --quiet");
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.stderrText.find(outJpg), std::string::npos) << r.stderrText;
    EXPECT_NE(r.stderrText.find(missing), std::string::npos) << r.stderrText;
    EXPECT_EQ(lineCount(r.stderrText), 1) << r.stderrText;
    EXPECT_FALSE(std::filesystem::exists(outJpg));

    // A PNG texture needs it too: the error names the texture file.
    const std::string png = writeTexturePng("needs_module.png");
    const std::string textured = tempPath("textured_missing.xml");
    writeTextFile(textured, texturedScene(png));
    r = runCommand(env + appPath("render") + " " + textured + " -o " + out + " --quiet --no-png");
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.stderrText.find(png), std::string::npos) << r.stderrText;
    EXPECT_NE(r.stderrText.find(missing), std::string::npos) << r.stderrText;
    EXPECT_EQ(lineCount(r.stderrText), 1) << r.stderrText;

    // A file that is not a shared library, and a library that is not the module.
    const std::string notLib = tempPath("not_a_library.so");
    writeTextFile(notLib, "not an ELF file\n");
    r = runCommand(std::string(kOiioModuleEnv) + "=" + notLib + " " + appPath("render") + " " + plain + " -o " +
                   outJpg + " --quiet");
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.stderrText.find(notLib), std::string::npos) << r.stderrText;
    EXPECT_NE(r.stderrText.find(outJpg), std::string::npos) << r.stderrText;
    EXPECT_EQ(lineCount(r.stderrText), 1) << r.stderrText;
    const std::string zlib = mappedLibrary("/libz.so");
    ASSERT_FALSE(zlib.empty());
    r = runCommand(std::string(kOiioModuleEnv) + "=" + zlib + " " + appPath("render") + " " + plain + " -o " + outJpg +
                   " --quiet");
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_NE(r.stderrText.find("not an iris OpenImageIO module"), std::string::npos) << r.stderrText;
    EXPECT_NE(r.stderrText.find(outJpg), std::string::npos) << r.stderrText;
    for (const std::string& p : {out, plain, png, textured, notLib, envExr, exrScene}) std::filesystem::remove(p);
}
