// Colour management through OpenColorIO with the shipped config: published sRGB matrix and
// transfer function, D65 white, ACEScg against OCIO's built-in AP1 → Rec.709 (Bradford) transform,
// config precedence (explicit > $OCIO > shipped) and errors naming the file.
#include <gtest/gtest.h>

#include <OpenColorIO/OpenColorIO.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

#include "core/error.h"
#include "spectral/color_management.h"
#include "spectral/color_space.h"
#include "spectral/spectrum_factory.h"
#include "spectral/xyz.h"
#include "tests/support/error_of.h"

using namespace iris;
using iris::test::errorOf;
namespace fs = std::filesystem;
namespace OCIO = OCIO_NAMESPACE;

namespace {

// Sets (or unsets) $OCIO for the lifetime of the object and restores the previous value.
class ScopedOcioEnv {
public:
    explicit ScopedOcioEnv(const std::optional<std::string>& value) {
        if (const char* old = std::getenv("OCIO")) old_ = old;
        if (value) ::setenv("OCIO", value->c_str(), 1);
        else ::unsetenv("OCIO");
    }
    ~ScopedOcioEnv() {
        if (old_) ::setenv("OCIO", old_->c_str(), 1);
        else ::unsetenv("OCIO");
    }

private:
    std::optional<std::string> old_;
};

fs::path tempDir() {
    static const fs::path dir = [] {
        fs::path d = fs::temp_directory_path() / ("iris_test_ocio_" + std::to_string(::getpid()));
        fs::create_directories(d);
        return d;
    }();
    return dir;
}

std::string readFile(const std::string& path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

vec3 convert1(const ColorManager& cm, vec3 c, const std::string& from, const std::string& to) {
    cm.convert(&c.x, 1, from, to);
    return c;
}

}  // namespace

TEST(ColorManagement, ShippedConfigByDefault) {
    ScopedOcioEnv env(std::nullopt);
    const ColorManager cm;
    EXPECT_EQ(cm.configPath(), ColorManager::shippedConfigPath());
    for (const char* cs : {kColorSpaceXYZ, kColorSpaceLinearRec709, "ACEScg", "ACES2065-1", "sRGB", "Raw"})
        EXPECT_TRUE(cm.hasColorSpace(cs)) << cs;
    EXPECT_FALSE(cm.hasColorSpace("no such space"));
    EXPECT_GE(cm.colorSpaces().size(), 6u);
}

TEST(ColorManagement, XyzToLinearRec709MatchesIecMatrix) {
    const ColorManager cm(ColorManager::shippedConfigPath());
    const vec3 inputs[] = {vec3(1, 0, 0), vec3(0, 1, 0), vec3(0, 0, 1), vec3(0.3f, 0.5f, 0.2f), vec3(2.0f, 1.5f, 0.1f),
                           vec3(0.05f, 0.02f, 0.9f)};
    // Interleaved buffer of all inputs: one call converts every pixel.
    std::vector<float> buf;
    for (const vec3& v : inputs) buf.insert(buf.end(), {v.x, v.y, v.z});
    cm.convert(buf.data(), std::size(inputs), kColorSpaceXYZ, kColorSpaceLinearRec709);
    for (size_t i = 0; i < std::size(inputs); ++i) {
        const vec3 x = inputs[i];
        // IEC 61966-2-1:1999 eq. (5).
        const vec3 expect(3.2406f * x.x - 1.5372f * x.y - 0.4986f * x.z, -0.9689f * x.x + 1.8758f * x.y + 0.0415f * x.z,
                          0.0557f * x.x - 0.2040f * x.y + 1.0570f * x.z);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(buf[3 * i + c], expect[c], 1e-4f) << i << " " << c;
    }
    // The D65 white point maps to RGB (1, 1, 1).
    const vec3 white = convert1(cm, vec3(0.9505f, 1.0f, 1.089f), kColorSpaceXYZ, kColorSpaceLinearRec709);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(white[c], 1.0f, 1e-3f);
    // And so does the film's XYZ of D65 scaled to Y = 1 (CIE tables, 1 nm).
    const SpectrumPtr d65 = makeD65Spectrum();
    const vec3 filmWhite(integrateXYZ([&](float l) { return d65->eval(l); }));
    const vec3 w2 = convert1(cm, filmWhite, kColorSpaceXYZ, kColorSpaceLinearRec709);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(w2[c], 1.0f, 1e-3f);
    // Round trip.
    const vec3 back = convert1(cm, convert1(cm, vec3(0.2f, 0.7f, 0.4f), kColorSpaceLinearRec709, kColorSpaceXYZ),
                               kColorSpaceXYZ, kColorSpaceLinearRec709);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(back[c], vec3(0.2f, 0.7f, 0.4f)[c], 1e-5f);
}

TEST(ColorManagement, SrgbEncodingAndDisplay) {
    const ColorManager cm(ColorManager::shippedConfigPath());
    // IEC 61966-2-1: V = 1.055 L^(1/2.4) − 0.055 above 0.0031308, else 12.92 L.
    const vec3 enc = convert1(cm, vec3(0.5f, 0.002f, 1.0f), kColorSpaceLinearRec709, "sRGB");
    EXPECT_NEAR(enc.x, 0.7354f, 1e-4f);
    EXPECT_NEAR(enc.y, 12.92f * 0.002f, 1e-4f);
    EXPECT_NEAR(enc.z, 1.0f, 1e-5f);
    // The default display/view (sRGB / Standard) is the same encoding.
    vec3 disp(0.5f, 0.002f, 1.0f);
    cm.toDisplay(&disp.x, 1, kColorSpaceLinearRec709);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(disp[c], enc[c], 1e-5f);
    vec3 disp2(0.5f, 0.002f, 1.0f);
    cm.toDisplay(&disp2.x, 1, kColorSpaceLinearRec709, "sRGB", "Standard");
    for (int c = 0; c < 3; ++c) EXPECT_EQ(disp2[c], disp[c]);
    // From XYZ: D65 white displays as code value 1.
    vec3 w(0.9505f, 1.0f, 1.089f);
    cm.toDisplay(&w.x, 1, kColorSpaceXYZ);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(w[c], 1.0f, 1e-3f);
    EXPECT_THROW(cm.toDisplay(&w.x, 1, kColorSpaceXYZ, "NoDisplay"), Error);
    EXPECT_THROW(cm.toDisplay(&w.x, 1, kColorSpaceXYZ, "sRGB", "NoView"), Error);
}

TEST(ColorManagement, AcesCgMatchesOcioBuiltinBradford) {
    const ColorManager cm(ColorManager::shippedConfigPath());
    // Reference: OCIO's own built-in "UTILITY - ACES-AP1_to_LINEAR-REC709_BFD" (exact Rec.709
    // matrix; ours uses the 4-digit IEC matrix, hence the 1e-3 tolerance).
    OCIO::BuiltinTransformRcPtr bt = OCIO::BuiltinTransform::Create();
    bt->setStyle("UTILITY - ACES-AP1_to_LINEAR-REC709_BFD");
    const OCIO::ConstConfigRcPtr raw = OCIO::Config::CreateRaw();
    const OCIO::ConstCPUProcessorRcPtr ref = raw->getProcessor(bt)->getDefaultCPUProcessor();
    for (const vec3& ap1 : {vec3(1, 0, 0), vec3(0, 1, 0), vec3(0, 0, 1), vec3(1, 1, 1), vec3(0.2f, 0.5f, 0.8f)}) {
        vec3 expect = ap1;
        ref->applyRGB(&expect.x);
        const vec3 got = convert1(cm, ap1, "ACEScg", kColorSpaceLinearRec709);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], expect[c], 1e-3f) << c;
    }
    // Through XYZ the IEC matrix cancels: AP1/AP0 → CIE-XYZ must equal OCIO's Bradford built-ins closely.
    const std::pair<const char*, const char*> viaXyz[] = {{"ACEScg", "UTILITY - ACES-AP1_to_CIE-XYZ-D65_BFD"},
                                                          {"ACES2065-1", "UTILITY - ACES-AP0_to_CIE-XYZ-D65_BFD"}};
    for (const auto& [space, style] : viaXyz) {
        OCIO::BuiltinTransformRcPtr b = OCIO::BuiltinTransform::Create();
        b->setStyle(style);
        const OCIO::ConstCPUProcessorRcPtr toXyz = raw->getProcessor(b)->getDefaultCPUProcessor();
        for (const vec3& v : {vec3(1, 0, 0), vec3(0, 1, 0), vec3(0, 0, 1), vec3(1, 1, 1), vec3(0.2f, 0.5f, 0.8f)}) {
            vec3 expect = v;
            toXyz->applyRGB(&expect.x);
            const vec3 got = convert1(cm, v, space, kColorSpaceXYZ);
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], expect[c], 2e-5f) << space << " " << c;
        }
    }
    const vec3 rt = convert1(cm, convert1(cm, vec3(0.3f, 0.6f, 0.1f), kColorSpaceLinearRec709, "ACEScg"), "ACEScg",
                             kColorSpaceLinearRec709);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(rt[c], vec3(0.3f, 0.6f, 0.1f)[c], 1e-5f);
}

TEST(ColorManagement, OcioEnvironmentVariableAndPrecedence) {
    // A copy of the shipped config with one more colour space (linear, ×2 to the reference).
    std::string text = readFile(ColorManager::shippedConfigPath());
    text += R"(
  - !<ColorSpace>
    name: test_extra
    family: Test
    bitdepth: 32f
    isdata: false
    allocation: uniform
    to_scene_reference: !<MatrixTransform> {matrix: [2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 1]}
)";
    const std::string path = (tempDir() / "extra.ocio").string();
    std::ofstream(path) << text;
    {
        ScopedOcioEnv env(path);
        const ColorManager cm;
        EXPECT_EQ(cm.configPath(), path);
        ASSERT_TRUE(cm.hasColorSpace("test_extra"));
        const vec3 v = convert1(cm, vec3(0.25f, 0.5f, 1.0f), "test_extra", kColorSpaceLinearRec709);
        EXPECT_NEAR(v.x, 0.5f, 1e-6f);
        EXPECT_NEAR(v.z, 2.0f, 1e-6f);
        // An explicit path wins over $OCIO.
        const ColorManager shipped(ColorManager::shippedConfigPath());
        EXPECT_FALSE(shipped.hasColorSpace("test_extra"));
    }
    {
        const std::string missing = (tempDir() / "missing_env.ocio").string();
        ScopedOcioEnv env(missing);
        EXPECT_NE(errorOf([] { ColorManager cm; }).find(missing), std::string::npos);
    }
}

TEST(ColorManagement, ErrorsNameTheFile) {
    const std::string missing = (tempDir() / "no_such_config.ocio").string();
    const std::string msg = errorOf([&] { ColorManager cm(missing); });
    EXPECT_NE(msg.find(missing), std::string::npos) << msg;
    // A name the file system refuses (ENAMETOOLONG) is "not found" too, not a filesystem_error.
    const std::string tooLong = (tempDir() / std::string(300, 'c')).string() + ".ocio";
    const std::string msgLong = errorOf([&] { ColorManager cm(tooLong); });
    EXPECT_NE(msgLong.find("OpenColorIO config not found"), std::string::npos) << msgLong;
    const std::string garbage = (tempDir() / "garbage.ocio").string();
    std::ofstream(garbage) << "this: is: not [an ocio config\n";
    const std::string msg2 = errorOf([&] { ColorManager cm(garbage); });
    EXPECT_NE(msg2.find(garbage), std::string::npos) << msg2;
    const ColorManager cm(ColorManager::shippedConfigPath());
    vec3 v(0.5f);
    const std::string msg3 = errorOf([&] { cm.convert(&v.x, 1, "CIE-XYZ", "bogus"); });
    EXPECT_NE(msg3.find("bogus"), std::string::npos) << msg3;
    EXPECT_NE(msg3.find(cm.configPath()), std::string::npos) << msg3;
    // Zero pixels is a no-op.
    cm.convert(nullptr, 0, kColorSpaceXYZ, kColorSpaceLinearRec709);
}
