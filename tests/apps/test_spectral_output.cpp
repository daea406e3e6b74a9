// `render --spectral-output`: the spectral EXR in the layout of Fichet et al. 2021 beside the
// colour image, its options and errors, and `compare` reading it (colour and per-band errors).
#include <gtest/gtest.h>

#include <filesystem>

#include "core/io/image.h"
#include "core/io/spectral_layout.h"
#include "tests/support/app_runner.h"

using namespace iris;
using namespace iris::testing;

namespace {

const char* kScene = R"(<scene version="3.0.0">
    <integrator type="path"/>
    <sensor type="perspective">
        <float name="fov" value="40"/>
        <transform name="to_world"><lookat origin="0, 0, -4" target="0, 0, 0" up="0, 1, 0"/></transform>
        <sampler type="independent"><integer name="sample_count" value="4"/></sampler>
        <film type="hdrfilm"><integer name="width" value="16"/><integer name="height" value="12"/></film>
    </sensor>
    <shape type="sphere"><bsdf type="diffuse"><rgb name="reflectance" value="0.8, 0.3, 0.1"/></bsdf></shape>
    <emitter type="constant"><float name="radiance" value="1"/></emitter>
</scene>
)";

std::string temp(const std::string& name) { return tempPath("iris_spectral_output", name); }

}  // namespace

TEST(SpectralOutput, WritesTheSpectralLayoutWithTheChosenBins) {
    const std::string scene = temp("s.xml"), out = temp("c.exr"), spec = temp("s.exr");
    writeTextFile(scene, kScene);
    const RunResult r = runCommand(appPath("render") + " " + scene + " -o " + out + " --no-png --quiet --spectral-output " +
                                   spec + " --spectral-bin-width 10");
    ASSERT_EQ(r.exitCode, 0) << r.stderrText;
    const Image img = readImage(spec);
    EXPECT_EQ(img.width, 16);
    EXPECT_EQ(img.height, 12);
    const SpectralImage s = spectralChannels(img, spec);
    ASSERT_EQ(s.bins(), 47);
    EXPECT_EQ(s.wavelengths.front(), 365.0);
    EXPECT_EQ(s.wavelengths.back(), 825.0);
    const ImageMetadata meta = readEXRMetadata(spec);
    EXPECT_EQ(metadataValue(meta, "spectralLayoutVersion"), "1.0");
    EXPECT_EQ(metadataValue(meta, "emissiveUnits"), "W.m^-2.sr^-1");
    EXPECT_EQ(metadataValue(meta, "iris.spectral_bin_width_nm"), "10");
    EXPECT_EQ(metadataValue(meta, "iris.spp"), "4");

    // compare: colour from the bins against the colour image, and one error line per band.
    const RunResult bands = runCommand(appPath("compare") + " " + spec + " " + spec + " --no-flip --per-channel");
    ASSERT_EQ(bands.exitCode, 0) << bands.stderrText;
    EXPECT_NE(bands.stdoutText.find("channel S0.555,000000nm"), std::string::npos) << bands.stdoutText;
    const RunResult colour = runCommand(appPath("compare") + " " + spec + " " + out + " --no-flip --json");
    ASSERT_EQ(colour.exitCode, 0) << colour.stderrText;
    EXPECT_NE(colour.stdoutText.find("\"channels\": 3"), std::string::npos) << colour.stdoutText;
}

TEST(SpectralOutput, RgbModeResumeAndBadWidthsAreRejected) {
    const std::string scene = temp("e.xml"), out = temp("e.exr"), spec = temp("es.exr");
    writeTextFile(scene, kScene);
    const std::string base = appPath("render") + " " + scene + " -o " + out + " --no-png --quiet --spectral-output " + spec;
    const RunResult rgb = runCommand(base + " --mode rgb");
    EXPECT_EQ(rgb.exitCode, 2);
    EXPECT_NE(rgb.stderrText.find("--spectral-output needs --mode spectral"), std::string::npos) << rgb.stderrText;
    const RunResult resume = runCommand(base + " --checkpoint " + temp("ck") + " --resume");
    EXPECT_EQ(resume.exitCode, 2) << resume.stderrText;
    const RunResult width = runCommand(base + " --spectral-bin-width 4");
    EXPECT_EQ(width.exitCode, 1);
    EXPECT_NE(width.stderrText.find("does not divide"), std::string::npos) << width.stderrText;
    EXPECT_FALSE(std::filesystem::exists(spec));
}
