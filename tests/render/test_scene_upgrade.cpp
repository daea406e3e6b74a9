// The upgrade pass (render/loader/scene_upgrade.h): a version 0.6 scene's spellings rewritten into
// Mitsuba 3's, the defaults of render/scene_defaults.h filled in, each object once; and the parser's
// refusal of an unsupported version with file and line; Mitsuba 0.6's models written as
// `convention` parameters (core/mitsuba_convention.h), which plugins read instead of the version.
#include <gtest/gtest.h>

#include <string>

#include "core/error.h"
#include "core/xml/xml_parser.h"
#include "render/loader/scene_loader.h"
#include "render/loader/scene_upgrade.h"
#include "render/scene_defaults.h"
#include "spectral/spectrum_params.h"
#include "tests/support/bsdf_test_util.h"
#include "tests/support/error_of.h"

using namespace iris;

namespace {

ParsedScene upgraded(const std::string& version, const std::string& body) {
    ParsedScene s = parseSceneString("<scene version=\"" + version + "\">\n" + body + "</scene>\n", ".");
    upgradeScene(s);
    return s;
}

/// The first top-level object with this tag (nullptr if none).
PropertiesPtr first(const ParsedScene& s, const std::string& tag) {
    for (const PropertiesPtr& p : s.objects)
        if (p->tag() == tag) return p;
    return nullptr;
}

/// The child of `p` with this tag (nullptr if none).
PropertiesPtr child(const Properties& p, const std::string& tag) {
    for (const PropertiesPtr& c : p.children())
        if (c->tag() == tag) return c;
    return nullptr;
}

std::string errorOf(const std::string& version, const std::string& body) {
    try {
        upgraded(version, body);
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(SceneUpgrade, ASingleValuedSpectrumIsANumberIn06AndAFlatSpectrumIn3) {
    const std::string body = "<emitter type=\"constant\"><spectrum name=\"radiance\" value=\"2\"/></emitter>\n";
    const PropertiesPtr e06 = first(upgraded("0.6.0", body), "emitter");
    const PropertiesPtr e3 = first(upgraded("3.0.0", body), "emitter");
    ASSERT_TRUE(e06 && e3);
    ASSERT_NE(e06->peek("radiance"), nullptr);
    EXPECT_TRUE(std::holds_alternative<float>(*e06->peek("radiance")));
    EXPECT_TRUE(std::holds_alternative<SpectrumValue>(*e3->peek("radiance")));
    // Read as an emitter's radiance: Mitsuba 3's flat spectrum 2; Mitsuba 0.6's 2 × D65 (Y = 1),
    // which is not flat.
    const SpectrumPtr flat = getSpectrum(*e3, "radiance", SpectrumKind::Illuminant);
    const SpectrumPtr d65 = getSpectrum(*e06, "radiance", SpectrumKind::Illuminant);
    EXPECT_FLOAT_EQ(flat->eval(450.0f), 2.0f);
    EXPECT_FLOAT_EQ(flat->eval(650.0f), 2.0f);
    EXPECT_GT(std::abs(d65->eval(450.0f) - d65->eval(650.0f)), 0.1f);
}

TEST(SceneUpgrade, CamelCaseNamesOf06BecomeSnakeCaseAnd3KeepsThem) {
    const std::string body = "<integrator type=\"path\"><integer name=\"maxDepth\" value=\"4\"/></integrator>\n";
    EXPECT_TRUE(first(upgraded("0.6.0", body), "integrator")->has("max_depth"));
    EXPECT_FALSE(first(upgraded("0.6.0", body), "integrator")->has("maxDepth"));
    EXPECT_TRUE(first(upgraded("3.0.0", body), "integrator")->has("maxDepth"));
    // Both spellings in one 0.6 object: one parameter given twice, reported at the later element.
    const std::string both = errorOf("0.6.0", "<integrator type=\"path\">\n<integer name=\"maxDepth\" value=\"4\"/>\n"
                                              "<integer name=\"max_depth\" value=\"5\"/>\n</integrator>\n");
    EXPECT_NE(both.find("<string>:4:"), std::string::npos) << both;
    EXPECT_NE(both.find("'max_depth' is specified twice"), std::string::npos) << both;
}

TEST(SceneUpgrade, A06ConductorGetsMitsuba06DefaultsAndExtEta) {
    const PropertiesPtr c06 = first(upgraded("0.6.0", "<bsdf type=\"conductor\"/>\n"), "bsdf");
    EXPECT_EQ(c06->getString("material"), "Cu");
    EXPECT_FLOAT_EQ(c06->getFloat("ext_ior"), 1.000277f);
    const PropertiesPtr c3 = first(upgraded("3.0.0", "<bsdf type=\"conductor\"/>\n"), "bsdf");
    EXPECT_FALSE(c3->has("material"));
    EXPECT_FALSE(c3->has("ext_ior"));
    // Given eta and k: no material; extEta is ext_ior.
    const PropertiesPtr ek = first(upgraded("0.6.0", "<bsdf type=\"roughconductor\"><float name=\"eta\" value=\"1\"/>"
                                                     "<float name=\"k\" value=\"2\"/><float name=\"extEta\" value=\"1.5\"/></bsdf>\n"),
                                   "bsdf");
    EXPECT_FALSE(ek->has("material"));
    EXPECT_FALSE(ek->has("ext_eta"));
    EXPECT_FLOAT_EQ(ek->getFloat("ext_ior"), 1.5f);
    const std::string both = errorOf("0.6.0", "<bsdf type=\"conductor\">\n<float name=\"extEta\" value=\"1.5\"/>\n"
                                              "<float name=\"ext_ior\" value=\"1.2\"/>\n</bsdf>\n");
    EXPECT_NE(both.find("<string>:4:"), std::string::npos) << both;
    EXPECT_NE(both.find("not both"), std::string::npos) << both;
}

TEST(SceneUpgrade, A06NormalmapHasMitsuba3sOptionsOff) {
    const std::string body = "<bsdf type=\"normalmap\"><boolean name=\"flipInvalidNormals\" value=\"true\"/></bsdf>\n";
    const PropertiesPtr n06 = first(upgraded("0.6.0", body), "bsdf");
    EXPECT_TRUE(n06->getBool("flip_invalid_normals"));  // given: kept
    EXPECT_FALSE(n06->getBool("use_shadowing_function"));
    EXPECT_FALSE(first(upgraded("3.0.0", body), "bsdf")->has("use_shadowing_function"));
}

TEST(SceneUpgrade, AReferencedObjectIsUpgradedOnce) {
    // Upgraded twice, the conductor would get its material twice ("specified twice").
    const ParsedScene s = upgraded("0.6.0", "<bsdf type=\"conductor\" id=\"metal\"/>\n"
                                            "<bsdf type=\"twosided\" id=\"a\"><ref id=\"metal\"/></bsdf>\n"
                                            "<bsdf type=\"twosided\" id=\"b\"><ref name=\"x\" id=\"metal\"/></bsdf>\n");
    EXPECT_EQ(first(s, "bsdf")->getString("material"), "Cu");
}

TEST(SceneUpgrade, AMissingIntegratorSensorFilmSamplerAndFilterComeFromTheDefaultsTable) {
    const ParsedScene s = upgraded("3.0.0", "<shape type=\"sphere\"/>\n");
    const PropertiesPtr integrator = first(s, "integrator");
    ASSERT_TRUE(integrator);
    EXPECT_EQ(integrator->type(), kDefaultIntegrator);
    const PropertiesPtr sensor = first(s, "sensor");
    ASSERT_TRUE(sensor);
    EXPECT_EQ(sensor->type(), kDefaultSensor);
    const PropertiesPtr film = child(*sensor, "film"), sampler = child(*sensor, "sampler");
    ASSERT_TRUE(film && sampler);
    EXPECT_EQ(film->type(), kDefaultFilm);
    EXPECT_EQ(sampler->type(), kDefaultSampler);
    EXPECT_EQ(sampler->getInt("sample_count"), kDefaultSampleCount);
    const PropertiesPtr filter = child(*film, "rfilter");
    ASSERT_TRUE(filter);
    EXPECT_EQ(filter->type(), kDefaultFilter);
    EXPECT_EQ(filter->objectCache(), s.cache.get());
}

TEST(SceneUpgrade, WhatTheSceneNamesIsKept) {
    const ParsedScene s = upgraded("3.0.0", "<integrator type=\"volpath\"/>\n"
                                            "<sensor type=\"orthographic\"><film type=\"ldrfilm\"><rfilter type=\"box\"/></film>"
                                            "<sampler name=\"sampler\" type=\"sobol\"/></sensor>\n");
    int integrators = 0, sensors = 0;
    for (const PropertiesPtr& p : s.objects) {
        integrators += p->tag() == "integrator";
        sensors += p->tag() == "sensor";
    }
    EXPECT_EQ(integrators, 1);
    EXPECT_EQ(sensors, 1);
    const PropertiesPtr sensor = first(s, "sensor");
    EXPECT_EQ(sensor->type(), "orthographic");
    EXPECT_EQ(sensor->children().size(), 1u);  // the film; the sampler is named
    EXPECT_EQ((*sensor->peekObject("sampler"))->type(), "sobol");
    const PropertiesPtr film = child(*sensor, "film");
    ASSERT_EQ(film->children().size(), 1u);
    EXPECT_EQ(film->children()[0]->type(), "box");
    // A film without a filter gets the default one, beside the scene's own sampler.
    const PropertiesPtr noFilter = child(*first(upgraded("3.0.0", "<sensor type=\"perspective\"><film type=\"hdrfilm\"/></sensor>\n"),
                                                "sensor"),
                                         "film");
    ASSERT_TRUE(child(*noFilter, "rfilter"));
    EXPECT_EQ(child(*noFilter, "rfilter")->type(), kDefaultFilter);
}

TEST(SceneUpgrade, AnUnsupportedVersionIsRefusedWithFileAndLine) {
    for (const char* v : {"1.0.0", "4.0.0", "x"}) {
        const std::string e = errorOf(v, "<shape type=\"sphere\"/>\n");
        EXPECT_NE(e.find("<string>:1:"), std::string::npos) << v << ": " << e;
        EXPECT_NE(e.find(v == std::string("x") ? "" : "unsupported scene version"), std::string::npos) << e;
    }
}

TEST(SceneUpgrade, A06FileGetsMitsuba06sModelsAsConventionParameters) {
    const std::string body =
        "<bsdf type=\"roughplastic\" id=\"rp\"/>\n"
        "<bsdf type=\"blendbsdf\" id=\"blend\"><bsdf type=\"diffuse\"/><bsdf type=\"mask\"><bsdf type=\"null\"/></bsdf></bsdf>\n"
        "<bsdf type=\"roughplastic\" id=\"mine\"><string name=\"convention\" value=\"mitsuba3\"/></bsdf>\n"
        "<emitter type=\"area\" id=\"e\"><spectrum name=\"radiance\" value=\"400:1, 700:2\"/></emitter>\n";
    const ParsedScene s06 = upgraded("0.6.0", body), s3 = upgraded("3.0.0", body);
    auto conventionOf = [](const Properties& p) -> std::string {
        const auto* v = p.peek("convention");
        return v ? std::get<std::string>(*v) : "";
    };
    const PropertiesPtr rp06 = first(s06, "bsdf"), rp3 = first(s3, "bsdf");
    ASSERT_TRUE(rp06 && rp3);
    EXPECT_EQ(conventionOf(*rp06), "mitsuba0.6");
    EXPECT_EQ(conventionOf(*rp3), "");  // Mitsuba 3's models need nothing written
    // Nested ones too, and only on the plugins with two models (a diffuse or null has one).
    const PropertiesPtr blend06 = s06.objects[1];
    EXPECT_EQ(conventionOf(*blend06), "mitsuba0.6");
    EXPECT_EQ(conventionOf(*blend06->children()[0]), "");
    EXPECT_EQ(conventionOf(*blend06->children()[1]), "mitsuba0.6");
    EXPECT_EQ(conventionOf(*blend06->children()[1]->children()[0]), "");
    // What the scene gives is kept.
    EXPECT_EQ(conventionOf(*s06.objects[2]), "mitsuba3");
    // A tabulated value carries Mitsuba 0.6's RGB rule in a 0.x file, Mitsuba 3's otherwise.
    const auto radiance = [](const ParsedScene& s) { return std::get<SpectrumValue>(*first(s, "emitter")->peek("radiance")); };
    EXPECT_EQ(radiance(s06).convention, MitsubaConvention::Mitsuba06);
    EXPECT_EQ(radiance(s3).convention, MitsubaConvention::Mitsuba3);
}

TEST(SceneUpgrade, A06PrincipledIsDisney) {
    EXPECT_EQ(first(upgraded("0.6.0", "<bsdf type=\"principled\"/>\n"), "bsdf")->type(), "disney");
    EXPECT_EQ(first(upgraded("3.0.0", "<bsdf type=\"principled\"/>\n"), "bsdf")->type(), "principled");
}

TEST(SceneUpgrade, ConventionInA3FileIsThe06Model) {
    // roughplastic's coat reflectance Fdr: Mitsuba 0.6's 1 − Td in a 0.x file, or in a 3.x file that
    // asks for it; Mitsuba 3's R_int (a darker base, docs/scene_format.md) otherwise.
    const std::initializer_list<test::Param> params = {{"alpha", 0.4f}, {"distribution", std::string("ggx")}};
    const SampledWavelengths rgb = SampledWavelengths::rgb(defaultChannelWavelengths());
    const test::BSDFInstance v0 = test::makeBSDFVersion(0, "roughplastic", params, rgb);
    const test::BSDFInstance v3 = test::makeBSDFVersion(3, "roughplastic", params, rgb);
    const test::BSDFInstance asked = test::makeBSDF(
        "roughplastic", {{"alpha", 0.4f}, {"distribution", std::string("ggx")}, {"convention", std::string("mitsuba0.6")}}, rgb);
    const vec3 wo = normalize(vec3(0.3f, 0.1f, 0.9f)), wi = normalize(vec3(-0.5f, 0.2f, 0.7f));
    const float f0 = v0.bsdf->eval(wo, wi, TransportMode::Radiance)[0];
    EXPECT_EQ(asked.bsdf->eval(wo, wi, TransportMode::Radiance)[0], f0);
    EXPECT_LT(v3.bsdf->eval(wo, wi, TransportMode::Radiance)[0], 0.95f * f0);
}

TEST(SceneUpgrade, AnUnknownConventionIsRefusedWithItsLine) {
    const std::string error = test::errorOf([] {
        loadSceneFromString("<scene version=\"3.0.0\">\n<shape type=\"sphere\">\n<bsdf type=\"roughplastic\">\n"
                            "<string name=\"convention\" value=\"mitsuba2\"/>\n</bsdf></shape></scene>", ".");
    });
    EXPECT_TRUE(test::contains(error, ":4:")) << error;
    EXPECT_TRUE(test::contains(error, "unknown convention 'mitsuba2' (known: mitsuba3, mitsuba0.6)")) << error;
    // A plugin with one model has no such parameter.
    const std::string one = test::errorOf([] {
        loadSceneFromString("<scene version=\"3.0.0\">\n<shape type=\"sphere\">\n<bsdf type=\"diffuse\">\n"
                            "<string name=\"convention\" value=\"mitsuba0.6\"/>\n</bsdf></shape></scene>", ".");
    });
    EXPECT_TRUE(test::contains(one, "unknown parameter 'convention'")) << one;
}
