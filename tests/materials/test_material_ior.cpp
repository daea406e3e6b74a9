// Indices of refraction across the materials: every BSDF that takes an index accepts a preset name
// (Mitsuba 3's `<string name="int_ior" value="bk7"/>`) and renders exactly as with its number; an
// unknown name is a file:line error listing the valid names; the thesis models' η_t read by the
// one reader comes back exactly (docs/materials.md, "Indices of refraction").
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/error.h"
#include "materials/fresnel.h"
#include "materials/thesis/thesis_channels.h"
#include "render/loader/scene_loader.h"
#include "spectral/ior_presets.h"
#include "tests/support/bsdf_test_util.h"

using namespace iris;
using namespace iris::test;

namespace {

using Params = std::initializer_list<Param>;

std::string S(const char* s) { return s; }

/// Same sampled directions, values and pdfs (bit for bit) for a few directions and samples, and
/// the same eval for the non-delta lobes.
void expectSameBSDF(const BSDFInstance& a, const BSDFInstance& b, const std::string& what) {
    for (float cosO : {0.9f, 0.5f, 0.15f}) {
        const vec3 wo = dirFromCos(cosO, 0.4f);
        for (float uc : {0.05f, 0.5f, 0.95f}) {
            const auto sa = a.bsdf->sample(wo, uc, vec2(0.3f, 0.7f), TransportMode::Radiance);
            const auto sb = b.bsdf->sample(wo, uc, vec2(0.3f, 0.7f), TransportMode::Radiance);
            ASSERT_EQ(bool(sa), bool(sb)) << what;
            if (!sa) continue;
            ASSERT_EQ(sa->wi, sb->wi) << what;
            ASSERT_EQ(sa->pdf, sb->pdf) << what;
            for (int k = 0; k < sa->f.size(); ++k) ASSERT_EQ(sa->f[k], sb->f[k]) << what << " entry " << k;
            if (sa->isSpecular()) continue;
            const SampledSpectrum ea = a.bsdf->eval(wo, sa->wi, TransportMode::Radiance);
            const SampledSpectrum eb = b.bsdf->eval(wo, sa->wi, TransportMode::Radiance);
            for (int k = 0; k < ea.size(); ++k) ASSERT_EQ(ea[k], eb[k]) << what << " entry " << k;
        }
    }
}

struct NamedCase {
    const char* type;
    std::vector<Param> named, numbers;
};

std::shared_ptr<Properties> propsOf(const char* type, const std::vector<Param>& params) {
    auto p = makeProps(type, {});
    for (const auto& [name, v] : params) p->set(name, v, {});
    return p;
}

std::string writeScene(const std::string& name, const std::string& bsdf) {
    const auto dir = std::filesystem::temp_directory_path() / ("iris_ior_tests_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    const auto path = dir / name;
    std::ofstream(path) << "<scene version=\"3.0.0\">\n<bsdf type=\"" << bsdf.substr(0, bsdf.find(' ')) << "\">\n"
                        << bsdf.substr(bsdf.find(' ') + 1) << "\n</bsdf>\n</scene>\n";
    return path.string();
}

}  // namespace

TEST(MaterialIOR, PresetNamesOnEveryBSDFThatTakesAnIndex) {
    const std::vector<NamedCase> cases = {
        {"dielectric", {{"int_ior", S("water")}, {"ext_ior", S("air")}}, {{"int_ior", 1.333f}, {"ext_ior", 1.000277f}}},
        {"thindielectric", {{"int_ior", S("pyrex")}}, {{"int_ior", 1.470f}}},
        {"roughdielectric", {{"int_ior", S("diamond")}, {"alpha", 0.3f}}, {{"int_ior", 2.419f}, {"alpha", 0.3f}}},
        {"plastic", {{"int_ior", S("bk7")}}, {{"int_ior", 1.5046f}}},
        {"roughplastic", {{"int_ior", S("acrylic glass")}, {"ext_ior", S("vacuum")}}, {{"int_ior", 1.49f}, {"ext_ior", 1.0f}}},
        {"principled", {{"eta", S("water")}}, {{"eta", 1.333f}}},
        {"conductor", {{"material", S("Au")}, {"ext_ior", S("water")}}, {{"material", S("Au")}, {"ext_ior", 1.333f}}},
        {"roughconductor", {{"material", S("Cu")}, {"ext_ior", S("ethanol")}, {"alpha", 0.2f}},
         {{"material", S("Cu")}, {"ext_ior", 1.361f}, {"alpha", 0.2f}}},
        {"thinfilm",
         {{"film_ior", S("water")}, {"ext_ior", S("air")}, {"substrate", S("dielectric")}, {"substrate_eta", S("bk7")},
          {"layer1_ior", S("diamond")}, {"layer1_thickness", 100.0f}},
         {{"film_ior", 1.333f}, {"ext_ior", 1.000277f}, {"substrate", S("dielectric")}, {"substrate_eta", 1.5046f},
          {"layer1_ior", 2.419f}, {"layer1_thickness", 100.0f}}},
        {"iridescent_diffuse", {{"int_ior", S("bk7")}, {"film_ior", S("fused quartz")}}, {{"int_ior", 1.5046f}, {"film_ior", 1.458f}}},
        {"granier", {{"eta_t", S("water")}, {"eta_i", S("air")}}, {{"eta_t", 1.333f}, {"eta_i", 1.000277f}}},
        {"proposed", {{"eta_t", S("bk7")}, {"eta_i", S("vacuum")}}, {{"eta_t", 1.5046f}, {"eta_i", 1.0f}}},
    };
    for (const auto& c : cases) {
        const SampledWavelengths rgb = SampledWavelengths::rgb(defaultChannelWavelengths());
        for (const SampledWavelengths& wl : {rgb, SampledWavelengths::sampleVisible(0.37f, 8)}) {
            const BSDFInstance named = makeBSDF(*propsOf(c.type, c.named), wl);
            const BSDFInstance numbers = makeBSDF(*propsOf(c.type, c.numbers), wl);
            expectSameBSDF(named, numbers, c.type);
        }
    }
}

TEST(MaterialIOR, PrincipledEtaIsMitsubasSpecular) {
    // Mitsuba 3: 0.08 specular = ((η − 1)/(η + 1))², so η = 1.5 is the default specular 0.5; in both
    // of iris's principled models (Mitsuba 3's `principled`, Disney 2012 `disney`).
    for (const char* type : {"principled", "disney"}) {
        const BSDFInstance eta = makeBSDF(type, {{"eta", 1.5f}});
        const BSDFInstance specular = makeBSDF(type, {{"specular", schlickF0FromEta(1.5f) / 0.08f}});
        expectSameBSDF(eta, specular, std::string(type) + " eta");
        EXPECT_THROW(makeBSDF(type, {{"eta", 1.5f}, {"specular", 0.5f}}), Error);
    }
    EXPECT_NEAR(schlickF0FromEta(1.5f) / 0.08f, 0.5f, 1e-6f);
    EXPECT_THROW(makeBSDF("disney", {{"eta", S("diamond")}}), Error);  // beyond Burley's 0.08 specular
    EXPECT_NO_THROW(makeBSDF("principled", {{"eta", S("diamond")}}));  // Mitsuba 3: any η (exact Fresnel)
}

TEST(MaterialIOR, UnknownNameIsAFileLineErrorListingTheNames) {
    // "<type> <parameter line>" per case; the parameter is on line 3 of the written scene.
    const std::vector<std::string> cases = {
        "dielectric <string name=\"int_ior\" value=\"glassy\"/>",
        "thindielectric <string name=\"ext_ior\" value=\"glassy\"/>",
        "roughdielectric <string name=\"int_ior\" value=\"glassy\"/>",
        "plastic <string name=\"int_ior\" value=\"glassy\"/>",
        "roughplastic <string name=\"ext_ior\" value=\"glassy\"/>",
        "principled <string name=\"eta\" value=\"glassy\"/>",
        "conductor <string name=\"ext_ior\" value=\"glassy\"/>",
        "roughconductor <string name=\"ext_ior\" value=\"glassy\"/>",
        "thinfilm <string name=\"film_ior\" value=\"glassy\"/>",
        "thinfilm <string name=\"substrate_eta\" value=\"glassy\"/>",
        "iridescent_diffuse <string name=\"int_ior\" value=\"glassy\"/>",
        "granier <string name=\"eta_t\" value=\"glassy\"/>",
        "proposed <string name=\"eta_i\" value=\"glassy\"/>",
    };
    int i = 0;
    for (const std::string& c : cases) {
        const std::string file = "unknown_ior_" + std::to_string(i++) + ".xml";
        try {
            loadScene(writeScene(file, c));
            ADD_FAILURE() << c << ": expected an iris::Error";
        } catch (const Error& e) {
            const std::string msg = e.what();
            EXPECT_NE(msg.find(file + ":3:"), std::string::npos) << msg;
            EXPECT_NE(msg.find("'glassy'"), std::string::npos) << msg;
            EXPECT_NE(msg.find(iorPresetList()), std::string::npos) << msg;
        }
    }
}

TEST(MaterialIOR, ThesisChannelIndexIsExactForEqualChannels) {
    // η_t given as one number (or three equal values) is that number at every sampled wavelength;
    // the former per-channel interpolation (1 − t)a + ta rounded it off (ChannelLerp test).
    for (const PropertyValue& v : {PropertyValue(1.7f), PropertyValue(RGBValue{vec3(1.6f)})}) {
        auto p = makeProps("granier", {{"eta_t", v}});
        const ThesisChannels ch = ThesisChannels::read(*p, "granier", vec3(1.5f, 1.6f, 1.8f));
        const float expected = ch.etaT.eval(kLambdaMin);
        for (float u = 0.0f; u < 1.0f; u += 0.013f) {
            const SampledWavelengths wl = SampledWavelengths::sampleVisible(u, 8);
            const SampledSpectrum eta = ch.etaT.sample(ch.of(wl));
            for (int k = 0; k < wl.size(); ++k) ASSERT_EQ(eta[k], expected) << wl.lambda(k);
        }
    }
    // RGB mode: the material's channel wavelengths stand for the channels (a spectrum η_t is
    // evaluated there), whatever the render's RGB wavelengths.
    SpectrumValue s;
    s.type = SpectrumValue::Type::Pairs;
    s.lambdas = {400, 700};
    s.values = {1.9f, 1.6f};
    auto p = makeProps("proposed", {{"eta_t", s}, {"wavelengths", RGBValue{vec3(650, 550, 450)}}});
    const ThesisChannels ch = ThesisChannels::read(*p, "proposed", vec3(1.8f, 1.7f, 1.6f));
    const SampledWavelengths render = SampledWavelengths::rgb(defaultChannelWavelengths());
    const SampledSpectrum eta = ch.etaT.sample(ch.of(render));
    for (int k = 0; k < 3; ++k) EXPECT_EQ(eta[k], ch.etaT.eval(vec3(650, 550, 450)[k]));
}
