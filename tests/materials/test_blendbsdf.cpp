// The `blendbsdf` plugin (materials/blendbsdf.cpp): eval and pdf are the linear blend, sampling
// picks a nested BSDF with probability 1 − w / w (Mitsuba 3: its sample unchanged; Mitsuba 0.6:
// consistent with eval and pdf, checked by the consistency and chi-square tests, which the
// Mitsuba 3 form is shown to fail), the albedo is the blend of the nested albedos in both forms,
// the nested order follows Mitsuba (names in alphanumeric order), and wrong blends are refused
// with their line.
#include <gtest/gtest.h>

#include "core/error.h"
#include "render/loader/scene_loader.h"
#include "tests/support/bsdf_test_util.h"
#include "tests/support/error_of.h"
#include "render/loader/scene_upgrade.h"

using namespace iris;
using namespace iris::test;

namespace {

const SampledWavelengths kRGB = SampledWavelengths::rgb(defaultChannelWavelengths());
constexpr TransportMode kRad = TransportMode::Radiance;

/// blendbsdf(weight, first, second) in a file of the given format version (0 = Mitsuba 0.6).
BSDFInstance makeBlend(float weight, std::shared_ptr<Properties> first, std::shared_ptr<Properties> second,
                       int version = 3) {
    auto props = makeProps("blendbsdf", {{"weight", weight}});
    props->setFormatVersion(version);
    first->setFormatVersion(version);
    second->setFormatVersion(version);
    props->addChild(first);
    props->addChild(second);
    upgradeObject(*props);  // as the loader reads it (the version's convention)
    return makeBSDF(*props, kRGB);
}

std::shared_ptr<Properties> diffuse(float r) { return makeProps("diffuse", {{"reflectance", r}}); }

std::string loadError(const std::string& body, const std::string& version = "3.0.0") {
    return test::errorOf([&] {
        loadSceneFromString("<scene version=\"" + version + "\">\n<shape type=\"sphere\">\n" + body + "</shape></scene>", ".");
    });
}

const auto has = test::contains;

}  // namespace

TEST(BlendBSDF, EvalAndPdfAreTheLinearBlend) {
    // Mitsuba 3 blendbsdf.cpp: f = (1 − w) f₀ + w f₁, pdf = (1 − w) pdf₀ + w pdf₁.
    auto blend = makeBlend(0.25f, diffuse(0.2f), diffuse(0.8f));
    const vec3 wo = dirFromCos(0.7f, 0.3f), wi = dirFromCos(0.4f, 2.0f);
    EXPECT_NEAR(blend.bsdf->eval(wo, wi, kRad)[0], (0.75f * 0.2f + 0.25f * 0.8f) / kPi, 1e-7f);
    EXPECT_NEAR(blend.bsdf->pdf(wo, wi, kRad), 0.4f / kPi, 1e-7f);
    EXPECT_TRUE(blend.bsdf->hasNonSpecular());
    // The extremes are the nested BSDFs themselves.
    auto first = makeBlend(0.0f, diffuse(0.2f), diffuse(0.8f));
    auto second = makeBlend(1.0f, diffuse(0.2f), diffuse(0.8f));
    EXPECT_NEAR(first.bsdf->eval(wo, wi, kRad)[1], 0.2f / kPi, 1e-7f);
    EXPECT_NEAR(second.bsdf->eval(wo, wi, kRad)[1], 0.8f / kPi, 1e-7f);
    for (float uc : {0.0f, 0.5f, 0x1.fffffep-1f}) {
        const auto a = first.bsdf->sample(wo, uc, vec2(0.3f, 0.8f), kRad);
        const auto b = second.bsdf->sample(wo, uc, vec2(0.3f, 0.8f), kRad);
        ASSERT_TRUE(a && b);
        EXPECT_NEAR(a->weight()[0], 0.2f, 1e-6f);
        EXPECT_NEAR(b->weight()[0], 0.8f, 1e-6f);
    }
}

TEST(BlendBSDF, Mitsuba3SamplesTheChosenBSDFUnchanged) {
    // uc > w: the first BSDF (probability 1 − w), with uc rescaled; its sample is returned as it is.
    auto blend = makeBlend(0.3f, makeProps("roughconductor", {{"alpha", 0.2f}}), diffuse(0.6f));
    auto rough = makeBSDF("roughconductor", {{"alpha", 0.2f}});
    auto diff = makeBSDF("diffuse", {{"reflectance", 0.6f}});
    const vec3 wo = dirFromCos(0.8f, 0.4f);
    const int n = 1000;
    int firsts = 0;
    for (int i = 0; i < n; ++i) {
        const float uc = (i + 0.5f) / n;
        const vec2 u(0.37f, 0.61f);
        const auto s = blend.bsdf->sample(wo, uc, u, kRad);
        ASSERT_TRUE(s);
        const auto d = uc > 0.3f ? rough.bsdf->sample(wo, (uc - 0.3f) / 0.7f, u, kRad) : diff.bsdf->sample(wo, uc / 0.3f, u, kRad);
        ASSERT_TRUE(d);
        firsts += uc > 0.3f;
        EXPECT_EQ(s->wi, d->wi);
        EXPECT_EQ(s->pdf, d->pdf);  // the nested pdf, not the blend's
        EXPECT_EQ(s->f[1], d->f[1]);
    }
    EXPECT_EQ(firsts, 700);
}

TEST(BlendBSDF, Mitsuba06SamplingIsConsistentAndPassesChiSquare) {
    auto blend = makeBlend(0.3f, makeProps("roughconductor", {{"alpha", 0.2f}}), diffuse(0.6f), 0);
    for (float c : {0.9f, 0.35f}) {
        const vec3 wo = dirFromCos(c, 0.4f);
        const auto k = checkConsistency(*blend.bsdf, wo, 5000);
        EXPECT_EQ(k.invalid, 0);
        EXPECT_LT(k.maxRelErrF, 1e-4f) << k.message;
        EXPECT_LT(k.maxRelErrPdf, 1e-4f) << k.message;
        Chi2Options opt;
        opt.numTests = 2;
        const auto chi = chi2Test(*blend.bsdf, wo, opt);
        EXPECT_TRUE(chi.passed) << chi.message;
    }
    // The check can fail: Mitsuba 3's form returns the nested pdf, not the blend's.
    auto m3 = makeBlend(0.3f, makeProps("roughconductor", {{"alpha", 0.2f}}), diffuse(0.6f), 3);
    const auto k3 = checkConsistency(*m3.bsdf, dirFromCos(0.9f, 0.4f), 5000);
    EXPECT_GT(k3.maxRelErrPdf, 0.1f);
}

TEST(BlendBSDF, AlbedoIsTheBlendOfTheNestedAlbedosWithADeltaLobe) {
    // A smooth dielectric (albedo A: R + T/η² in radiance transport) blended with a diffuse 0.6 at
    // w = 0.4: albedo 0.6 A + 0.4 · 0.6, whichever form samples it.
    const vec3 wo = dirFromCos(0.6f, 1.0f);
    auto dielectric = makeBSDF("dielectric", {});
    const auto a = albedo(*dielectric.bsdf, wo, 200000);
    for (int version : {3, 0}) {
        auto blend = makeBlend(0.4f, makeProps("dielectric", {}), diffuse(0.6f), version);
        EXPECT_TRUE(blend.bsdf->flags() & kBSDFSpecular);
        const auto al = albedo(*blend.bsdf, wo, 200000);
        for (int ch = 0; ch < 3; ++ch)
            EXPECT_NEAR(al[ch].mean, 0.6 * a[ch].mean + 0.24, 4 * (al[ch].stderr_ + a[ch].stderr_) + 1e-5) << version;
    }
    // A wrong blend (w = 0.5 instead of 0.4) is outside the tolerance.
    auto wrong = makeBlend(0.5f, makeProps("dielectric", {}), diffuse(0.6f));
    const auto aw = albedo(*wrong.bsdf, wo, 200000);
    EXPECT_GT(std::abs(aw[0].mean - (0.6 * a[0].mean + 0.24)), 10 * (aw[0].stderr_ + a[0].stderr_));
}

TEST(BlendBSDF, NestedOrderIsMitsubas) {
    // Named nested bsdfs go by the alphanumeric order of their names, whatever their order in the
    // file; weight 0 is the first.
    const std::string scene =
        "<bsdf type=\"blendbsdf\" id=\"b\"><float name=\"weight\" value=\"0\"/>\n"
        "<bsdf type=\"diffuse\" name=\"z_second\"><float name=\"reflectance\" value=\"0.8\"/></bsdf>\n"
        "<bsdf type=\"diffuse\" name=\"a_first\"><float name=\"reflectance\" value=\"0.2\"/></bsdf>\n</bsdf>";
    auto props = makeProps("blendbsdf", {{"weight", 0.0f}});
    auto second = diffuse(0.8f);
    auto first = diffuse(0.2f);
    props->set("z_second", PropertiesPtr(second), SourceLocation{"<test>", 1});
    props->set("a_first", PropertiesPtr(first), SourceLocation{"<test>", 2});
    auto b = makeBSDF(*props, kRGB);
    const vec3 wo = dirFromCos(0.7f, 0.3f), wi = dirFromCos(0.4f, 2.0f);
    EXPECT_NEAR(b.bsdf->eval(wo, wi, kRad)[0], 0.2f / kPi, 1e-7f);
    EXPECT_EQ(loadError(scene + "\n"), "");
}

TEST(BlendBSDF, WrongBlendsAreRefusedWithTheirLine) {
    const std::string one = loadError("<bsdf type=\"blendbsdf\">\n<bsdf type=\"diffuse\"/>\n</bsdf>\n");
    EXPECT_TRUE(has(one, "<string>:3: blendbsdf: expected two nested bsdfs, got 1")) << one;
    const std::string three =
        loadError("<bsdf type=\"blendbsdf\">\n<bsdf type=\"diffuse\"/><bsdf type=\"diffuse\"/><bsdf type=\"diffuse\"/>\n</bsdf>\n");
    EXPECT_TRUE(has(three, "expected two nested bsdfs, got 3")) << three;
    for (const char* bad : {"1.5", "-0.25"}) {
        const std::string out = loadError(std::string("<bsdf type=\"blendbsdf\">\n<float name=\"weight\" value=\"") + bad +
                                          "\"/>\n<bsdf type=\"diffuse\"/><bsdf type=\"conductor\"/></bsdf>\n");
        EXPECT_TRUE(has(out, "<string>:4: blendbsdf: weight")) << out;
        EXPECT_TRUE(has(out, "outside [0, 1]")) << out;
    }
    const std::string unknown =
        loadError("<bsdf type=\"blendbsdf\">\n<float name=\"wieght\" value=\"0.5\"/>\n<bsdf type=\"diffuse\"/><bsdf type=\"diffuse\"/></bsdf>\n");
    EXPECT_TRUE(has(unknown, "unknown parameter 'wieght'")) << unknown;
    // Accepted: the default weight, a texture weight, a 0.6 file.
    EXPECT_EQ(loadError("<bsdf type=\"blendbsdf\"><bsdf type=\"diffuse\"/><bsdf type=\"conductor\"/></bsdf>\n"), "");
    EXPECT_EQ(loadError("<bsdf type=\"blendbsdf\"><texture name=\"weight\" type=\"checkerboard\"/>"
                        "<bsdf type=\"diffuse\"/><bsdf type=\"conductor\"/></bsdf>\n"),
              "");
    EXPECT_EQ(loadError("<bsdf type=\"blendbsdf\"><bsdf type=\"diffuse\"/><bsdf type=\"diffuse\"/></bsdf>\n", "0.6.0"), "");
}
