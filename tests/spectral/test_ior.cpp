// The one IOR type (spectral/ior.h), its interpolation (spectral/channel_lerp.h), the presets
// (spectral/ior_presets.h) and the one reader of IOR parameters (spectral/ior_params.h).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <limits>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/source_tree.h"
#include "spectral/ior.h"
#include "spectral/ior_params.h"
#include "spectral/ior_presets.h"
#include "spectral/spectrum_factory.h"
#include "tests/support/error_of.h"
#include "tests/support/spectrum_pairs.h"

using namespace iris;
using iris::test::errorOf;
using iris::test::spectrumPairs;

namespace {

Properties props(std::initializer_list<std::pair<std::string, PropertyValue>> values) {
    Properties p("bsdf", "test", SourceLocation{"scene.xml", 3});
    int line = 4;
    for (const auto& [name, v] : values) p.set(name, v, SourceLocation{"scene.xml", line++});
    return p;
}


}  // namespace

TEST(ChannelLerp, EqualNeighboursComeBackExactly) {
    // Between two equal channel values the interpolation returns that value, not (1 − t)a + ta.
    const vec3 ch = defaultChannelWavelengths();  // R, G, B: 1.6 at R and G, 1.9 at B
    const ChannelLerp l(vec3(1.6f, 1.6f, 1.9f), ch);
    int naiveDiffers = 0;
    for (float lambda = ch.y; lambda <= ch.x; lambda += 0.37f) {
        ASSERT_EQ(l(lambda), 1.6f) << lambda;
        naiveDiffers += lerp((lambda - ch.y) / (ch.x - ch.y), 1.6f, 1.6f) != 1.6f;
    }
    // The test can fail: the plain lerp (the thesis models' former interpolation) rounds off 1.6.
    EXPECT_GT(naiveDiffers, 0);
    // Unequal neighbours: the plain lerp, endpoints exact, constant outside.
    EXPECT_EQ(l(ch.z), 1.9f);
    EXPECT_EQ(l(400.0f), 1.9f);
    EXPECT_EQ(l(700.0f), 1.6f);
    EXPECT_EQ(l(485.0f), lerp((485.0f - ch.z) / (ch.y - ch.z), 1.9f, 1.6f));
}

TEST(IOR, FormsEvaluateAndSample) {
    const SampledWavelengths rgb = SampledWavelengths::rgb(defaultChannelWavelengths());
    const SampledWavelengths spectral = SampledWavelengths::sampleVisible(0.3f, 8);
    // Three equal channel values are a constant: the same value at every wavelength.
    const IOR flat = IOR::perChannel(vec3(1.4f));
    EXPECT_EQ(flat.kind(), IOR::Kind::Constant);
    EXPECT_FALSE(flat.isDispersive());
    for (int k = 0; k < spectral.size(); ++k) EXPECT_EQ(flat.sample(spectral)[k], 1.4f);
    // A triple at other channel wavelengths: exact in RGB mode whatever the render's channels.
    const IOR triple = IOR::perChannel(vec3(1.5f, 1.6f, 1.8f), vec3(650, 530, 440));
    const SampledSpectrum t = triple.sample(SampledWavelengths::rgb(vec3(600, 500, 400)));
    EXPECT_EQ(t[0], 1.5f);
    EXPECT_EQ(t[1], 1.6f);
    EXPECT_EQ(t[2], 1.8f);
    EXPECT_EQ(triple.eval(530.0f), 1.6f);
    for (int k = 0; k < spectral.size(); ++k) EXPECT_EQ(triple.sample(spectral)[k], triple.eval(spectral.lambda(k)));
    // A spectrum follows its own RGB-mode rule: an rgb-defined one returns its triple.
    const IOR upsampled = IOR::tabulated(makeRGBSpectrum(vec3(0.2f, 0.5f, 1.1f), SpectrumKind::Unbounded));
    EXPECT_EQ(upsampled.sample(rgb)[2], 1.1f);
    const IOR measured = IOR::tabulated(makePiecewiseLinearSpectrum({400, 700}, {1.6f, 1.5f}, SpectrumKind::Unbounded));
    EXPECT_EQ(measured.sample(rgb)[0], measured.eval(defaultChannelWavelengths().x));
    EXPECT_TRUE(measured.isDispersive());
    const IOR::Range r = measured.range();
    EXPECT_FLOAT_EQ(r.min, 1.5f);
    EXPECT_FLOAT_EQ(r.max, 1.6f);
    // at(wl, k) is entry k of sample(wl), for every form and mode.
    for (const IOR& ior : {flat, triple, upsampled, measured, IOR::cauchy(1.5f, 0.01f)})
        for (const SampledWavelengths& wl : {rgb, spectral})
            for (int k = 0; k < wl.size(); ++k) EXPECT_EQ(ior.at(wl, k), ior.sample(wl)[k]);
    // Cauchy with B = 0 is not dispersive.
    EXPECT_FALSE(IOR::cauchy(1.5f, 0.0f).isDispersive());
}

TEST(IorPresets, MitsubaTable) {
    float eta = 0;
    ASSERT_TRUE(lookupIORPreset("BK7", &eta));  // case-insensitive, as Mitsuba's lookup_ior
    EXPECT_EQ(eta, 1.5046f);
    ASSERT_TRUE(lookupIORPreset("carbon dioxide", &eta));
    EXPECT_EQ(eta, 1.00045f);
    EXPECT_EQ(presetIOR("air").eval(500.0f), 1.000277f);
    EXPECT_THROW(presetIOR("glassy"), Error);
    EXPECT_NE(iorPresetList().find("vacuum, helium, hydrogen, air"), std::string::npos);
}

TEST(IorPresets, DocsListTheTable) {
    // docs/materials.md lists "name value, name value, ..." after "checked against it by" and
    // before "An unknown name": the same names, in order, with the same values.
    std::ifstream in(sourcePath("docs/materials.md"));
    ASSERT_TRUE(in) << "docs/materials.md";
    std::stringstream ss;
    ss << in.rdbuf();
    const std::string doc = ss.str();
    const size_t from = doc.find('\n', doc.find("`IorPresets.DocsListTheTable`"));
    const size_t to = doc.find("An unknown name", from);
    ASSERT_NE(from, std::string::npos);
    ASSERT_NE(to, std::string::npos);
    std::string list = doc.substr(from, to - from);
    for (char& c : list)
        if (c == '\n') c = ' ';
    std::vector<std::string> names;
    std::stringstream items(list);
    for (std::string item; std::getline(items, item, ',');) {
        item.erase(0, item.find_first_not_of(' '));
        item.erase(item.find_last_not_of(" .") + 1);
        const size_t space = item.rfind(' ');
        ASSERT_NE(space, std::string::npos) << item;
        const std::string name = item.substr(0, space);
        float eta = 0;
        ASSERT_TRUE(lookupIORPreset(name, &eta)) << name;
        EXPECT_EQ(eta, std::stof(item.substr(space + 1))) << name;
        names.push_back(name);
    }
    EXPECT_EQ(names, iorPresetNames());
}

TEST(IorParams, EveryFormOfAnIndex) {
    const IOR def = IOR::constant(1.5f);
    EXPECT_EQ(readIOR(props({}), "int_ior", def).eval(500.0f), 1.5f);
    EXPECT_EQ(readIOR(props({{"int_ior", 1.7f}}), "int_ior", def).eval(500.0f), 1.7f);
    EXPECT_EQ(readIOR(props({{"int_ior", int64_t(2)}}), "int_ior", def).eval(500.0f), 2.0f);
    EXPECT_EQ(readIOR(props({{"int_ior", std::string("Water")}}), "int_ior", def).eval(500.0f), 1.333f);
    EXPECT_EQ(readIOR(props({{"int_ior", std::string("1.25")}}), "int_ior", def).eval(500.0f), 1.25f);
    const IOR rgb = readIOR(props({{"film_ior", RGBValue{vec3(1.4f, 1.5f, 1.6f)}},
                                   {"film_ior_wavelengths", VectorValue{vec3(600, 500, 400)}}}),
                            "film_ior", def);
    EXPECT_EQ(rgb.kind(), IOR::Kind::PerChannel);
    EXPECT_EQ(rgb.eval(500.0f), 1.5f);
    EXPECT_EQ(readIOR(props({{"eta", VectorValue{vec3(1.4f, 1.5f, 1.6f)}}}), "eta", def).eval(525.0f), 1.5f);
    EXPECT_EQ(readIOR(props({{"int_ior", spectrumPairs({400, 700}, {1.6f, 1.5f})}}), "int_ior", def).kind(), IOR::Kind::Tabulated);
    SpectrumValue c;
    c.constant = 1.45f;
    EXPECT_EQ(readIOR(props({{"int_ior", c}}), "int_ior", def).kind(), IOR::Kind::Constant);
    // Formulas, named after the base of the parameter (int_ior → int_, eta_t → eta_t_).
    const IOR cauchy = readIOR(props({{"int_cauchy_a", 1.5f}, {"int_cauchy_b", 0.01f}}), "int_ior", def);
    EXPECT_FLOAT_EQ(cauchy.eval(500.0f), 1.5f + 0.01f / 0.25f);
    const IOR etaT = readIOR(props({{"eta_t_cauchy_a", 1.5f}}), "eta_t", def);
    EXPECT_EQ(etaT.kind(), IOR::Kind::Cauchy);
    const IOR sellmeier = readIOR(props({{"layer1_sellmeier_b", VectorValue{vec3(1.03961212f, 0.231792344f, 1.01046945f)}},
                                         {"layer1_sellmeier_c", VectorValue{vec3(0.00600069867f, 0.0200179144f, 103.560653f)}}}),
                                  "layer1_ior", def);
    EXPECT_NEAR(sellmeier.eval(587.6f), 1.5168f, 2e-4f);  // Schott N-BK7 n_d
    // The material's channel wavelengths (the thesis models' `wavelengths`).
    const IOR thesis = readIOR(props({{"eta_t", RGBValue{vec3(1.5f, 1.6f, 1.8f)}}}), "eta_t", def, vec3(700, 600, 500));
    EXPECT_EQ(thesis.eval(600.0f), 1.6f);
}

TEST(IorParams, InvalidValuesAreLocatedErrors) {
    const IOR def = IOR::constant(1.5f);
    // An unknown name lists the valid ones, at the parameter's line.
    std::string msg = errorOf([&] { readIOR(props({{"int_ior", std::string("glassy")}}), "int_ior", def); });
    EXPECT_NE(msg.find("scene.xml:4"), std::string::npos) << msg;
    EXPECT_NE(msg.find("'glassy'"), std::string::npos) << msg;
    EXPECT_NE(msg.find(iorPresetList()), std::string::npos) << msg;
    // Not positive, not finite, at the parameter's line and naming it.
    for (float bad : {0.0f, -1.5f, std::numeric_limits<float>::infinity(), std::numeric_limits<float>::quiet_NaN()}) {
        msg = errorOf([&] { readIOR(props({{"ext_ior", bad}}), "ext_ior", def); });
        EXPECT_NE(msg.find("scene.xml:4"), std::string::npos) << bad << ": " << msg;
        EXPECT_NE(msg.find("'ext_ior'"), std::string::npos) << msg;
    }
    // A triple with one negative channel, a spectrum dipping below 0, a Sellmeier pole at 500 nm.
    EXPECT_THROW(readIOR(props({{"film_ior", RGBValue{vec3(1.5f, -1.0f, 1.6f)}}}), "film_ior", def), Error);
    EXPECT_THROW(readIOR(props({{"film_ior", spectrumPairs({400, 700}, {-0.1f, 1.5f})}}), "film_ior", def), Error);
    EXPECT_THROW(readIOR(props({{"int_sellmeier_b", VectorValue{vec3(1, 0, 0)}}, {"int_sellmeier_c", VectorValue{vec3(0.25f, 0, 0)}}}),
                         "int_ior", def),
                 Error);
    // Only one form; wavelengths only for the rgb form.
    EXPECT_THROW(readIOR(props({{"int_ior", 1.5f}, {"int_cauchy_a", 1.5f}}), "int_ior", def), Error);
    EXPECT_THROW(readIOR(props({{"int_ior", 1.5f}, {"int_ior_wavelengths", VectorValue{vec3(600, 500, 400)}}}), "int_ior", def),
                 Error);
    // Extinction: ≥ 0, no names.
    const IOR zero = IOR::constant(0.0f);
    EXPECT_EQ(readIOR(props({{"film_k", 0.0f}}), "film_k", zero, IorQuantity::Extinction).eval(500.0f), 0.0f);
    EXPECT_THROW(readIOR(props({{"film_k", -0.1f}}), "film_k", zero, IorQuantity::Extinction), Error);
    EXPECT_THROW(readIOR(props({{"film_k", std::string("water")}}), "film_k", zero, IorQuantity::Extinction), Error);
    // A constant index: names and floats, not a dispersive one.
    EXPECT_EQ(readConstantIOR(props({{"ext_ior", std::string("water")}}), "ext_ior", 1.0f), 1.333f);
    EXPECT_EQ(readConstantIOR(props({{"ext_ior", RGBValue{vec3(1.2f)}}}), "ext_ior", 1.0f), 1.2f);
    EXPECT_THROW(readConstantIOR(props({{"ext_ior", RGBValue{vec3(1.2f, 1.3f, 1.4f)}}}), "ext_ior", 1.0f), Error);
}

TEST(IorParams, ConductorOpticsReadRgbAsMitsuba) {
    // Mitsuba's conductor `eta`: an rgb is an upsampled unbounded spectrum, not the per-channel form.
    const IOR eta = readIOR(props({{"eta", RGBValue{vec3(0.2f, 0.5f, 1.1f)}}}), "eta", IOR(), IorQuantity::ConductorOptics);
    EXPECT_EQ(eta.kind(), IOR::Kind::Tabulated);
    const SampledWavelengths wl = SampledWavelengths::sampleVisible(0.4f, 4);
    const SampledSpectrum expected = makeRGBSpectrum(vec3(0.2f, 0.5f, 1.1f), SpectrumKind::Unbounded)->sample(wl);
    for (int k = 0; k < wl.size(); ++k) EXPECT_EQ(eta.sample(wl)[k], expected[k]);
    EXPECT_EQ(readIOR(props({{"k", 0.0f}}), "k", IOR(), IorQuantity::ConductorOptics).eval(500.0f), 0.0f);
}
