// The `mask` and `null` bsdfs (materials/mask.cpp): eval/pdf/sample at opacity 0, 1 and 0.3 in
// Mitsuba 3's and Mitsuba 0.6's conventions, a texture opacity read from a grey+alpha PNG (sRGB
// decoded, alpha ignored), and the errors of a wrong mask.
#include <gtest/gtest.h>

#include <filesystem>
#include <unistd.h>

#include "core/error.h"
#include "core/io/image.h"
#include "core/srgb_transfer.h"
#include "core/xml/xml_values.h"
#include "render/loader/scene_loader.h"
#include "tests/support/bsdf_test_util.h"
#include "tests/support/error_of.h"
#include "render/loader/scene_upgrade.h"

using namespace iris;
using namespace iris::test;

namespace {

const SampledWavelengths kRGB = SampledWavelengths::rgb(defaultChannelWavelengths());

/// mask(opacity, diffuse(reflectance)) in a file of the given format version (0 = Mitsuba 0.6).
BSDFInstance makeMask(float opacity, float reflectance, int version = 3) {
    auto props = makeProps("mask", {{"opacity", opacity}});
    props->setFormatVersion(version);
    props->addChild(makeProps("diffuse", {{"reflectance", reflectance}}));
    upgradeObject(*props);  // as the loader reads it (the version's convention)
    return makeBSDF(*props, kRGB);
}

constexpr TransportMode kRad = TransportMode::Radiance;

}  // namespace

TEST(MaskBSDF, OpaqueIsTheNestedBSDF) {
    auto mask = makeMask(1.0f, 0.6f);
    auto diffuse = makeBSDF("diffuse", {{"reflectance", 0.6f}});
    EXPECT_TRUE(mask.bsdf->flags() & kBSDFNull);
    EXPECT_TRUE(mask.bsdf->hasNonSpecular());
    const vec3 wo = dirFromCos(0.7f, 0.3f), wi = dirFromCos(0.4f, 2.0f);
    EXPECT_EQ(mask.bsdf->eval(wo, wi, kRad)[1], diffuse.bsdf->eval(wo, wi, kRad)[1]);
    EXPECT_EQ(mask.bsdf->pdf(wo, wi, kRad), diffuse.bsdf->pdf(wo, wi, kRad));
    for (float uc : {0.0f, 0.5f, 0x1.fffffep-1f}) {
        const auto s = mask.bsdf->sample(wo, uc, vec2(0.3f, 0.8f), kRad);
        const auto d = diffuse.bsdf->sample(wo, uc, vec2(0.3f, 0.8f), kRad);
        ASSERT_TRUE(s && d);
        EXPECT_FALSE(s->isNull());
        EXPECT_EQ(s->wi, d->wi);
        EXPECT_EQ(s->pdf, d->pdf);
        EXPECT_EQ(s->f[0], d->f[0]);
    }
}

TEST(MaskBSDF, TransparentPassesStraightThroughFromBothSides) {
    auto mask = makeMask(0.0f, 0.6f);
    const vec3 wi = dirFromCos(0.4f, 2.0f);
    for (float c : {0.7f, -0.7f}) {
        const vec3 wo = dirFromCos(c, 0.3f);
        EXPECT_EQ(mask.bsdf->eval(wo, wi, kRad)[0], 0.0f);
        EXPECT_EQ(mask.bsdf->pdf(wo, wi, kRad), 0.0f);
        for (float uc : {0.0f, 0.5f, 0x1.fffffep-1f}) {
            const auto s = mask.bsdf->sample(wo, uc, vec2(0.3f, 0.8f), kRad);
            ASSERT_TRUE(s);
            EXPECT_TRUE(s->isNull() && s->isSpecular() && s->isTransmission());
            EXPECT_EQ(s->wi, -wo);
            EXPECT_EQ(s->pdf, 1.0f);
            EXPECT_EQ(s->eta, 1.0f);
            for (int k = 0; k < 3; ++k) EXPECT_NEAR(s->weight()[k], 1.0f, 1e-6f);
        }
    }
}

TEST(MaskBSDF, HalfOpaqueMitsuba3) {
    // opacity 0.3: f = 0.3 f_nested, pdf = 0.3 pdf_nested; the nested lobe is chosen when uc < 0.3
    // and its sample is the nested one unchanged (Mitsuba 3 src/bsdfs/mask.cpp), the pass-through
    // has probability 0.7 and weight 1.
    auto mask = makeMask(0.3f, 0.6f);
    auto diffuse = makeBSDF("diffuse", {{"reflectance", 0.6f}});
    const vec3 wo = dirFromCos(0.7f, 0.3f), wi = dirFromCos(0.4f, 2.0f);
    EXPECT_NEAR(mask.bsdf->eval(wo, wi, kRad)[2], 0.3f * 0.6f / kPi, 1e-7f);
    EXPECT_NEAR(mask.bsdf->pdf(wo, wi, kRad), 0.3f * diffuse.bsdf->pdf(wo, wi, kRad), 1e-7f);
    const int n = 1000;
    int nulls = 0;
    for (int i = 0; i < n; ++i) {
        const float uc = (i + 0.5f) / n;
        const auto s = mask.bsdf->sample(wo, uc, vec2(0.3f, 0.8f), kRad);
        ASSERT_TRUE(s);
        if (s->isNull()) {
            ++nulls;
            EXPECT_EQ(s->wi, -wo);
            EXPECT_NEAR(s->pdf, 0.7f, 1e-6f);
            EXPECT_NEAR(s->weight()[0], 1.0f, 1e-6f);
        } else {
            const auto d = diffuse.bsdf->sample(wo, uc / 0.3f, vec2(0.3f, 0.8f), kRad);
            EXPECT_EQ(s->wi, d->wi);
            EXPECT_EQ(s->pdf, d->pdf);  // the nested pdf, not 0.3 × it
            EXPECT_NEAR(s->weight()[0], 0.6f, 1e-6f);
        }
    }
    EXPECT_EQ(nulls, 700);
    // Albedo (white furnace of the BSDF): 0.3 · 0.6 + 0.7.
    const auto al = albedo(*mask.bsdf, wo, 200000);
    EXPECT_NEAR(al[0].mean, 0.3 * 0.6 + 0.7, 4 * al[0].stderr_ + 1e-6);
}

TEST(MaskBSDF, HalfOpaqueMitsuba06IsConsistent) {
    // Mitsuba 0.6 weighs the nested sample consistently: f = 0.3 f_nested, pdf = 0.3 pdf_nested.
    auto mask = makeMask(0.3f, 0.6f, 0);
    for (float c : {0.9f, 0.4f}) {
        const vec3 wo = dirFromCos(c, 0.3f);
        const auto k = checkConsistency(*mask.bsdf, wo, 5000);
        EXPECT_EQ(k.invalid, 0);
        EXPECT_GT(k.nonSpecular, 1000);
        EXPECT_GT(k.specular, 3000);
        EXPECT_LT(k.maxRelErrF, 1e-5f) << k.message;
        EXPECT_LT(k.maxRelErrPdf, 1e-5f) << k.message;
        const auto al = albedo(*mask.bsdf, wo, 200000);
        EXPECT_NEAR(al[1].mean, 0.3 * 0.6 + 0.7, 4 * al[1].stderr_ + 1e-6);
    }
}

TEST(MaskBSDF, NullIsThePassThroughAlone) {
    auto null = makeBSDF("null", {});
    EXPECT_FALSE(null.bsdf->hasNonSpecular());
    EXPECT_TRUE(null.bsdf->isSpecularOnly());
    const vec3 wo = dirFromCos(-0.2f, 1.0f);
    EXPECT_EQ(null.bsdf->eval(wo, -wo, kRad)[0], 0.0f);
    EXPECT_EQ(null.bsdf->pdf(wo, -wo, kRad), 0.0f);
    const auto s = null.bsdf->sample(wo, 0.9f, vec2(0.5f), kRad);
    ASSERT_TRUE(s && s->isNull());
    EXPECT_EQ(s->wi, -wo);
    EXPECT_NEAR(s->weight()[1], 1.0f, 1e-6f);
}

TEST(MaskBSDF, OpacityFromAGreyAlphaPngIsSrgbDecodedAndIgnoresAlpha) {
    // A 3×1 grey + alpha PNG like Mitsuba's leaf_mask.png: grey 0, 128, 255; alpha 255, 0, 128.
    namespace fs = std::filesystem;
    const fs::path dir = fs::temp_directory_path() / ("iris_mask_tests_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    Image img(3, 1, 2);
    const float grey[3] = {0.0f, 128.0f / 255.0f, 1.0f}, alpha[3] = {1.0f, 0.0f, 128.0f / 255.0f};
    for (int x = 0; x < 3; ++x) {
        img.at(x, 0, 0) = grey[x];
        img.at(x, 0, 1) = alpha[x];
    }
    const std::string png = (dir / "mask.png").string();
    writeLDR(png, img);
    const std::string xml = R"(<scene version="3.0.0"><shape type="sphere"><bsdf type="mask">
        <texture name="opacity" type="bitmap"><string name="filename" value=")" + png +
                            R"("/><string name="filter_type" value="nearest"/></texture>
        <bsdf type="diffuse"><float name="reflectance" value="1"/></bsdf></bsdf></shape></scene>)";
    const SceneDescription d = loadSceneFromString(xml, dir.string());
    ASSERT_EQ(d.shapes.size(), 1u);
    const Material& m = *d.shapes[0].material;
    const vec3 wo = dirFromCos(1.0f), wi = dirFromCos(1.0f);
    const float expected[3] = {0.0f, srgbToLinear(128.0f / 255.0f), 1.0f};  // Mitsuba: raw = false
    for (int x = 0; x < 3; ++x) {
        Arena arena;
        SampledWavelengths wl = kRGB;
        ShadingPoint sp;
        sp.tex.uv = vec2((x + 0.5f) / 3.0f, 0.5f);
        const BSDF* b = m.getBSDF(sp, wl, arena);
        ASSERT_TRUE(b);
        EXPECT_NEAR(b->eval(wo, wi, kRad)[0] * kPi, expected[x], 1e-5f) << x;
    }
    fs::remove_all(dir);
}

TEST(MaskBSDF, WrongMasksAreRefusedWithTheirLine) {
    const auto err = [](const std::string& body, const std::string& version = "3.0.0") {
        try {
            loadSceneFromString("<scene version=\"" + version + "\">\n<shape type=\"sphere\">\n" + body + "</shape></scene>", ".");
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    const auto has = test::contains;
    const std::string noNested = err("<bsdf type=\"mask\"><float name=\"opacity\" value=\"0.5\"/></bsdf>\n");
    EXPECT_TRUE(has(noNested, "<string>:3: mask: no nested bsdf")) << noNested;
    const std::string two = err("<bsdf type=\"mask\">\n<bsdf type=\"diffuse\"/>\n<bsdf type=\"conductor\"/>\n</bsdf>\n");
    EXPECT_TRUE(has(two, "<string>:5: mask: more than one nested bsdf")) << two;
    for (const char* bad : {"1.5", "-0.25"}) {
        const std::string out = err(std::string("<bsdf type=\"mask\">\n<float name=\"opacity\" value=\"") + bad +
                                    "\"/>\n<bsdf type=\"diffuse\"/></bsdf>\n");
        EXPECT_TRUE(has(out, "<string>:4: mask: opacity")) << out;
        EXPECT_TRUE(has(out, "outside [0, 1]")) << out;
    }
    const std::string bad06 = err("<bsdf type=\"mask\">\n<rgb name=\"opacity\" value=\"0.5 1.5 0.5\"/>\n<bsdf type=\"diffuse\"/></bsdf>\n", "0.6.0");
    EXPECT_TRUE(has(bad06, "<string>:4: mask: opacity 1.5")) << bad06;
    const std::string unknown = err("<bsdf type=\"mask\">\n<float name=\"opacty\" value=\"0.5\"/>\n<bsdf type=\"diffuse\"/></bsdf>\n");
    EXPECT_TRUE(has(unknown, "unknown parameter 'opacty'")) << unknown;
    // Accepted: the ends of the range, a named nested bsdf, the default opacity.
    EXPECT_EQ(err("<bsdf type=\"mask\"><float name=\"opacity\" value=\"1\"/><bsdf type=\"diffuse\"/></bsdf>\n"), "");
    EXPECT_EQ(err("<bsdf type=\"mask\"><float name=\"opacity\" value=\"0\"/><bsdf type=\"diffuse\" name=\"material\"/></bsdf>\n"), "");
    EXPECT_EQ(err("<bsdf type=\"mask\"><bsdf type=\"diffuse\"/></bsdf>\n", "0.6.0"), "");
}
