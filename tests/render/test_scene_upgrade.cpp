// The upgrade pass (render/loader/scene_upgrade.h): a version 0.6 scene's spellings rewritten into
// Mitsuba 3's, the defaults of render/scene_defaults.h filled in, each object once; and the parser's
// refusal of an unsupported version with file and line.
#include <gtest/gtest.h>

#include <string>

#include "core/error.h"
#include "core/xml/xml_parser.h"
#include "render/loader/scene_upgrade.h"
#include "render/scene_defaults.h"
#include "spectral/spectrum_params.h"

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
