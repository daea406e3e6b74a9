// Tests of Mitsuba 3's `principled` and `principledthin` (materials/principled_mitsuba.cpp):
// each lobe against its closed form (Mitsuba's clearcoat without 1/(4 cosθv cosθl), the exact
// dielectric Fresnel of the main lobe, Burley 2015's diffuse + retro-reflection, the Walter
// transmission, the thin sheet's mirrored transmission), chi-square sampling / pdf consistency on
// both sides of the surface, energy bounds, reciprocity of the reflection lobes, the version
// split (`principled` in a 0.x scene is the Disney 2012 `disney`, bit for bit), textures on every
// parameter, and bad input with file:line.
#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "core/error.h"
#include "core/registry.h"
#include "materials/fresnel.h"
#include "materials/microfacet.h"
#include "materials/principled_terms.h"
#include "render/loader/scene_loader.h"
#include "tests/support/bsdf_test_util.h"
#include "render/loader/scene_upgrade.h"

namespace iris {
namespace {

using test::makeBSDF;
constexpr TransportMode kRad = TransportMode::Radiance;

vec3 dir(float cosTheta, float phi) { return test::dirFromCos(cosTheta, phi); }

TEST(PrincipledMitsubaTerms, DiffuseFormsAgreeAndEtaInvertsSpecular) {
    // [B15]'s (1 − F_L/2)(1 − F_V/2) + R_R(...) is [B12]'s product with F_D90 = 0.5 + R_R.
    for (float r : {0.0f, 0.3f, 1.0f})
        for (float cl : {1.0f, 0.6f, 0.1f})
            for (float cv : {0.9f, 0.2f})
                for (float cd : {1.0f, 0.5f})
                    EXPECT_NEAR(principled::burley2015DiffuseFactor(cl, cv, cd, r),
                                principled::burleyDiffuseFactor(cl, cv, cd, r), 1e-5f);
    for (float s : {0.01f, 0.5f, 0.7f, 1.0f})
        EXPECT_NEAR(schlickF0FromEta(principled::etaFromSpecular(s)), 0.08f * s, 1e-6f);
    EXPECT_NEAR(principled::etaFromSpecular(0.7f), 1.61993f, 1e-4f);
    // Schlick weight: from outside (η > 1) the incident cosine; from inside the transmitted one.
    EXPECT_FLOAT_EQ(principled::schlickWeightMitsuba(0.6f, 1.5f), std::pow(0.4f, 5.0f));
    const float ct = std::sqrt(1.0f - (1.0f - 0.81f) * 1.5f * 1.5f);
    EXPECT_NEAR(principled::schlickWeightMitsuba(-0.9f, 1.5f), std::pow(1.0f - ct, 5.0f), 1e-6f);
    EXPECT_FLOAT_EQ(principled::schlickWeightMitsuba(-0.1f, 1.5f), 1.0f);  // total internal reflection
}

// Fails before this change (principled was Burley's: Schlick F with F0 = 0.08 specular, and a
// clearcoat divided by 4 cosθv cosθl): the main lobe uses the exact dielectric Fresnel.
TEST(PrincipledMitsuba, MainLobeUsesExactDielectricFresnel) {
    const float specular = 0.7f, r = 0.4f;
    auto inst = makeBSDF("principled", {{"base_color", 0.0f}, {"specular", specular}, {"roughness", r}});
    const float eta = principled::etaFromSpecular(specular);
    const MicrofacetDistribution ggx(MicrofacetType::GGX, r * r, r * r);
    for (float cv : {0.9f, 0.4f, 0.1f})
        for (float cl : {0.95f, 0.5f, 0.15f}) {
            const vec3 wo = dir(cv, 0.3f), wi = dir(cl, 2.6f);
            const vec3 h = glm::normalize(wo + wi);
            const float expect = fresnelDielectric(glm::dot(wo, h), eta) * ggx.D(h) * ggx.G(wi, wo, h) / (4 * cv * cl);
            EXPECT_NEAR(inst.bsdf->eval(wo, wi, kRad)[1], expect, 1e-5f * expect + 1e-9f) << cv << " " << cl;
        }
}

// Fails before this change: Mitsuba 3's clearcoat is f = 0.25 clearcoat F_cc D_GTR1 G_cc, without
// Burley's 1/(4 cosθv cosθl) (4 cosθv cosθl times Burley's).
TEST(PrincipledMitsuba, ClearcoatHasNoCosineDenominator) {
    // base 0 and specular 0 (η = 1): only the clearcoat is left.
    for (float gloss : {0.0f, 0.6f}) {
        auto inst = makeBSDF("principled", {{"base_color", 0.0f}, {"specular", 0.0f}, {"clearcoat", 0.8f},
                                            {"clearcoat_gloss", gloss}});
        const MicrofacetDistribution g25(MicrofacetType::GGX, 0.25f, 0.25f);
        const float alpha = principled::clearcoatAlpha(gloss);
        for (float cv : {0.95f, 0.5f, 0.2f})
            for (float cl : {0.9f, 0.45f, 0.1f}) {
                const vec3 wo = dir(cv, 0.1f), wi = dir(cl, 3.0f);
                const vec3 h = glm::normalize(wo + wi);
                const float fcc = 0.04f + 0.96f * std::pow(1.0f - glm::dot(wo, h), 5.0f);
                const float expect = 0.25f * 0.8f * fcc * principled::gtr1D(h.z, alpha) * g25.G(wi, wo, h);
                EXPECT_NEAR(inst.bsdf->eval(wo, wi, kRad)[0], expect, 1e-5f * expect + 1e-9f) << cv << " " << cl;
            }
    }
}

TEST(PrincipledMitsuba, DiffuseSheenAndFlatness) {
    // specular 0 → η = 1 → no specular lobe; base colour, roughness 0.8.
    const vec3 base(0.8f, 0.5f, 0.2f);
    const float r = 0.8f;
    auto diffuse = makeBSDF("principled", {{"base_color", RGBValue{base}}, {"specular", 0.0f}, {"roughness", r}});
    auto flat = makeBSDF("principled", {{"base_color", RGBValue{base}}, {"specular", 0.0f}, {"roughness", r},
                                        {"flatness", 0.6f}});
    auto sheen = makeBSDF("principled", {{"base_color", RGBValue{base}}, {"specular", 0.0f}, {"roughness", r},
                                         {"sheen", 0.7f}, {"sheen_tint", 0.5f}, {"metallic", 0.2f}});
    const float lum = principled::luminanceMitsuba(base);
    for (float cv : {0.9f, 0.3f})
        for (float cl : {0.8f, 0.2f}) {
            const vec3 wo = dir(cv, 0.0f), wi = dir(cl, 2.0f);
            const vec3 h = glm::normalize(wo + wi);
            const float cd = glm::dot(wi, h);
            const float fd = principled::burleyDiffuseFactor(cl, cv, cd, r);
            const float ss = principled::subsurfaceFactor(cl, cv, cd, r);
            const float fh = std::pow(1.0f - cd, 5.0f);
            for (int c = 0; c < 3; ++c) {
                EXPECT_NEAR(diffuse.bsdf->eval(wo, wi, kRad)[c], base[c] * fd * kInvPi, 1e-6f);
                EXPECT_NEAR(flat.bsdf->eval(wo, wi, kRad)[c], base[c] * lerp(0.6f, fd, ss) * kInvPi, 1e-6f);
                // Sheen: sheen (1 − metallic) F_H mix(1, Ctint, sheen_tint), not × (1 − spec_trans).
                const float sh = 0.7f * 0.8f * fh * lerp(0.5f, 1.0f, base[c] / lum);
                EXPECT_NEAR(sheen.bsdf->eval(wo, wi, kRad)[c], 0.8f * base[c] * fd * kInvPi + sh, 1e-6f);
            }
        }
}

TEST(PrincipledMitsuba, TransmissionIsWalterWithSqrtBaseColour) {
    const float eta = 1.4f, r = 0.5f;
    const vec3 base(0.64f, 0.25f, 0.09f);
    auto inst = makeBSDF("principled", {{"base_color", RGBValue{base}}, {"eta", eta}, {"roughness", r},
                                        {"spec_trans", 0.75f}});
    EXPECT_TRUE(inst.bsdf->flags() & kBSDFTransmission);
    const MicrofacetDistribution ggx(MicrofacetType::GGX, r * r, r * r);
    for (float cv : {0.9f, 0.5f})
        for (float cl : {-0.8f, -0.3f}) {
            const vec3 wo = dir(cv, 0.2f), wi = dir(cl, 2.8f);
            vec3 h = glm::normalize(wo + eta * wi);
            if (h.z < 0) h = -h;
            const float dv = glm::dot(wo, h), dl = glm::dot(wi, h);
            if (!(dv > 0 && dl < 0)) continue;
            const float F = fresnelDielectric(dv, eta);
            const float t = 0.75f * (1 - F) * ggx.D(h) * ggx.G(wi, wo, h) * std::abs(dv * dl) /
                            (cv * std::abs(cl) * sqr(dv + eta * dl));
            for (int c = 0; c < 3; ++c) {
                EXPECT_NEAR(inst.bsdf->eval(wo, wi, kRad)[c], std::sqrt(base[c]) * t, 1e-5f * t);
                EXPECT_NEAR(inst.bsdf->eval(wo, wi, TransportMode::Importance)[c], std::sqrt(base[c]) * t * eta * eta,
                            1e-5f * t * eta * eta);
            }
        }
    // From inside only the dielectric lobes: reflection bsdf·F, no diffuse.
    const vec3 wo = dir(-0.7f, 0.5f), wi = dir(-0.6f, 3.4f);
    const vec3 h = -glm::normalize(wo + wi);
    const float expect = 0.75f * fresnelDielectric(glm::dot(wo, h), eta) * ggx.D(h) * ggx.G(wi, wo, h) / (4 * 0.7f * 0.6f);
    EXPECT_NEAR(inst.bsdf->eval(wo, wi, kRad)[0], expect, 1e-5f * expect);
}

TEST(PrincipledThin, LobesAgainstTheirDefinitions) {
    const vec3 base(0.7f, 0.1f, 0.1f);
    const float eta = 1.33f, r = 0.4f, st = 0.6f, dtParam = 0.8f, dt = dtParam / 2;
    auto inst = makeBSDF("principledthin", {{"base_color", RGBValue{base}}, {"eta", eta}, {"roughness", r},
                                            {"spec_trans", st}, {"diff_trans", dtParam}});
    const MicrofacetDistribution refl(MicrofacetType::GGX, r * r, r * r);
    const float rt = (0.65f * eta - 0.35f) * r;
    const MicrofacetDistribution trans(MicrofacetType::GGX, rt * rt, rt * rt);
    for (float side : {1.0f, -1.0f})  // symmetric: the same from the back
        for (float cv : {0.9f, 0.4f})
            for (float cl : {0.7f, 0.25f, -0.7f, -0.25f}) {
                const vec3 v = dir(cv, 0.3f), l = dir(cl, 2.9f);
                const vec3 lr(l.x, l.y, std::abs(l.z));
                const vec3 h = glm::normalize(v + lr);
                const float F = fresnelDielectric(glm::dot(v, h), eta);
                const float cd = glm::dot(h, l);
                const float acl = std::abs(cl);
                for (int c = 0; c < 3; ++c) {
                    float expect;
                    if (cl > 0)
                        expect = st * F * refl.D(h) * refl.G(l, v, h) / (4 * cv * acl) +
                                 (1 - st) * (1 - dt) * base[c] * principled::burleyDiffuseFactor(acl, cv, cd, r) * kInvPi;
                    else
                        expect = (glm::dot(l, h) < 0 ? st * base[c] * (1 - F) * trans.D(h) * trans.G(l, v, h) / (4 * cv * acl)
                                                     : 0.0f) +
                                 (1 - st) * dt * base[c] * kInvPi;
                    const float got = inst.bsdf->eval(v * side, l * side, kRad)[c];
                    EXPECT_NEAR(got, expect, 1e-5f * expect + 1e-7f) << side << " " << cv << " " << cl << " " << c;
                }
            }
}

struct Config {
    const char* type;
    std::vector<test::Param> params;
};

std::vector<Config> samplingConfigs() {
    const RGBValue base{vec3(0.8f, 0.45f, 0.2f)};
    return {
        {"principled", {{"base_color", base}, {"roughness", 0.3f}}},
        {"principled", {{"base_color", base}, {"roughness", 0.15f}, {"anisotropic", 0.8f}, {"metallic", 0.4f},
                        {"clearcoat", 0.9f}, {"sheen", 0.5f}, {"specular", 0.7f}}},
        {"principled", {{"base_color", base}, {"roughness", 0.6f}, {"flatness", 0.7f}, {"spec_tint", 0.5f},
                        {"sheen", 1.0f}, {"sheen_tint", 1.0f}, {"clearcoat", 0.5f}, {"clearcoat_gloss", 0.8f}}},
        {"principled", {{"base_color", base}, {"roughness", 0.3f}, {"spec_trans", 0.7f}, {"eta", 1.5f}}},
        {"principled", {{"base_color", base}, {"roughness", 0.5f}, {"spec_trans", 1.0f}, {"anisotropic", 0.5f},
                        {"eta", 1.33f}, {"main_specular_sampling_rate", 2.0f}, {"diffuse_reflectance_sampling_rate", 0.5f}}},
        {"principled", {{"base_color", base}, {"roughness", 0.4f}, {"spec_trans", 0.5f}, {"eta", 0.8f},
                        {"clearcoat", 0.6f}, {"clearcoat_sampling_rate", 3.0f}}},
        {"principledthin", {{"base_color", base}, {"roughness", 0.3f}}},
        {"principledthin", {{"base_color", base}, {"roughness", 0.25f}, {"spec_trans", 0.6f}, {"diff_trans", 0.8f},
                            {"eta", 1.33f}, {"anisotropic", 0.7f}, {"sheen", 0.5f}, {"spec_tint", 0.4f}}},
        {"principledthin", {{"base_color", base}, {"roughness", 0.5f}, {"spec_trans", 1.0f}, {"eta", 1.8f},
                            {"specular_transmittance_sampling_rate", 2.0f}}},
        {"principledthin", {{"base_color", base}, {"spec_trans", 0.3f}, {"diff_trans", 2.0f}, {"flatness", 0.5f},
                            {"diffuse_transmittance_sampling_rate", 0.3f}}},
    };
}

test::BSDFInstance makeConfig(const Config& c) {
    auto p = test::makeProps(c.type, {});
    for (const auto& [name, v] : c.params) p->set(name, v, {});
    return makeBSDF(*p, SampledWavelengths::rgb(defaultChannelWavelengths()));
}

TEST(PrincipledMitsubaSampling, ChiSquareConsistencyAndPdfOnBothSides) {
    const auto configs = samplingConfigs();
    const float coss[] = {0.9f, 0.4f, 0.08f, -0.6f};  // −: viewer inside / behind the thin sheet
    const int numTests = int(configs.size() * std::size(coss));
    int index = 0;
    for (const auto& c : configs) {
        auto inst = makeConfig(c);
        for (float co : coss) {
            const vec3 wo = dir(co, 0.4f);
            for (TransportMode mode : {TransportMode::Radiance, TransportMode::Importance}) {
                test::Chi2Options opt;
                opt.numTests = 2 * numTests;
                opt.thetaBins = 40;
                opt.phiBins = 80;
                opt.samples = 400000;
                opt.seed = 11 + index;
                opt.mode = mode;
                const auto chi = test::chi2Test(*inst.bsdf, wo, opt);
                EXPECT_TRUE(chi.passed) << "config " << index << " (" << c.type << ") cos " << co << ": " << chi.message;
            }
            const auto cons = test::checkConsistency(*inst.bsdf, wo);
            EXPECT_EQ(cons.invalid, 0) << "config " << index << " cos " << co << ": " << cons.message;
            EXPECT_LT(cons.maxRelErrF, 1e-4f) << "config " << index << " cos " << co << ": " << cons.message;
            EXPECT_LT(cons.maxRelErrPdf, 1e-4f) << "config " << index << " cos " << co << ": " << cons.message;
            const auto pi = test::pdfIntegral(*inst.bsdf, wo);
            EXPECT_LE(pi.mean, 1.0 + 5 * pi.stderr_ + 1e-3) << "config " << index << " cos " << co;
        }
        ++index;
    }
}

TEST(PrincipledMitsubaSampling, ReflectionLobesAreReciprocal) {
    for (const auto& c : samplingConfigs()) {
        bool transmits = false;
        for (const auto& [name, v] : c.params) transmits |= name == "spec_trans" || name == "diff_trans";
        if (transmits || std::string(c.type) == "principledthin") continue;
        auto inst = makeConfig(c);
        EXPECT_LT(test::reciprocityError(*inst.bsdf), 1e-3f);
    }
}

TEST(PrincipledMitsubaFurnace, DielectricAndMetalLobesDoNotGainEnergy) {
    // White base colour: spec_trans 1 (a rough dielectric interface, R + T ≤ 1, single scattering)
    // and metallic 1 (Schlick F ≤ 1) never exceed 1 by more than 4 standard errors; the thin sheet
    // with spec_trans 1 neither.
    const std::vector<Config> cases = {
        {"principled", {{"base_color", 1.0f}, {"spec_trans", 1.0f}, {"roughness", 0.3f}}},
        {"principled", {{"base_color", 1.0f}, {"spec_trans", 1.0f}, {"roughness", 0.8f}, {"eta", 1.8f}}},
        {"principled", {{"base_color", 1.0f}, {"metallic", 1.0f}, {"roughness", 0.5f}, {"anisotropic", 0.6f}}},
        {"principledthin", {{"base_color", 1.0f}, {"spec_trans", 1.0f}, {"roughness", 0.3f}}},
        {"principledthin", {{"base_color", 1.0f}, {"spec_trans", 1.0f}, {"roughness", 0.7f}, {"eta", 1.5f}}},
    };
    for (const auto& c : cases) {
        auto inst = makeConfig(c);
        const bool transmits = inst.bsdf->flags() & kBSDFTransmission;
        for (float co : {1.0f, 0.6f, 0.2f, -0.5f}) {
            const auto all = test::albedo(*inst.bsdf, dir(co, 0.2f), 200000);
            if (!transmits && co < 0) {  // opaque: nothing from inside
                EXPECT_TRUE(all.empty());
                continue;
            }
            ASSERT_FALSE(all.empty()) << c.type << " cos " << co;
            const auto a = all[0];
            EXPECT_LE(a.mean, 1.0 + 4 * a.stderr_) << c.type << " cos " << co;
            EXPECT_GT(a.mean, 0.2) << c.type << " cos " << co;
        }
    }
}

TEST(PrincipledMitsuba, VersionZeroSceneIsDisney2012BitForBit) {
    auto make = [](const std::string& type, int version) {
        auto p = test::makeProps(type, {{"base_color", RGBValue{vec3(0.3f, 0.6f, 0.8f)}}, {"roughness", 0.3f},
                                        {"clearcoat", 0.7f}, {"sheen", 0.4f}, {"metallic", 0.2f}});
        p->setFormatVersion(version);
        upgradeObject(*p);  // as the loader reads it
        return makeBSDF(*p, SampledWavelengths::rgb(defaultChannelWavelengths()));
    };
    auto v0 = make("principled", 0), disney = make("disney", 3), v3 = make("principled", 3);
    bool differs = false;
    for (float cv : {0.9f, 0.3f})
        for (float cl : {0.8f, 0.2f}) {
            const vec3 wo = dir(cv, 0.1f), wi = dir(cl, 2.5f);
            const SampledSpectrum a = v0.bsdf->eval(wo, wi, kRad), b = disney.bsdf->eval(wo, wi, kRad);
            for (int c = 0; c < 3; ++c) EXPECT_EQ(a[c], b[c]);
            EXPECT_EQ(v0.bsdf->pdf(wo, wi, kRad), disney.bsdf->pdf(wo, wi, kRad));
            differs |= v3.bsdf->eval(wo, wi, kRad)[0] != a[0];
        }
    EXPECT_TRUE(differs);  // version 3: Mitsuba 3's model
}

TEST(PrincipledMitsuba, TexturesOnEveryParameter) {
    // Each float parameter as a checkerboard (color0 = a, color1 = b): the BSDF at a point of
    // either cell equals the one with that constant.
    auto checker = [](float a, float b) {
        auto t = std::make_shared<Properties>("texture", "checkerboard", SourceLocation{"<test>", 0});
        t->set("color0", a, SourceLocation{});
        t->set("color1", b, SourceLocation{});
        return t;
    };
    struct P {
        const char* type;
        const char* name;
        float a, b;
    };
    const std::vector<P> params = {
        {"principled", "roughness", 0.2f, 0.7f},      {"principled", "anisotropic", 0.1f, 0.9f},
        {"principled", "metallic", 0.3f, 0.8f},       {"principled", "spec_trans", 0.2f, 0.6f},
        {"principled", "spec_tint", 0.1f, 0.9f},      {"principled", "sheen", 0.2f, 0.9f},
        {"principled", "sheen_tint", 0.3f, 1.0f},     {"principled", "flatness", 0.1f, 0.8f},
        {"principled", "clearcoat", 0.4f, 0.9f},      {"principled", "clearcoat_gloss", 0.2f, 0.7f},
        {"principledthin", "roughness", 0.2f, 0.7f},  {"principledthin", "anisotropic", 0.1f, 0.9f},
        {"principledthin", "spec_trans", 0.2f, 0.8f}, {"principledthin", "spec_tint", 0.1f, 0.9f},
        {"principledthin", "sheen", 0.2f, 0.9f},      {"principledthin", "sheen_tint", 0.3f, 1.0f},
        {"principledthin", "flatness", 0.1f, 0.8f},   {"principledthin", "diff_trans", 0.4f, 1.4f},
        {"principledthin", "eta", 1.2f, 1.6f},
    };
    auto props = [](const P& q) {  // the other lobes on, so that the parameter matters
        auto p = test::makeProps(q.type, {{"base_color", RGBValue{vec3(0.6f, 0.3f, 0.2f)}}});
        for (const char* other : {"sheen", "spec_trans"})
            if (std::string(other) != q.name) p->set(other, 0.5f, SourceLocation{});
        return p;
    };
    Arena arena;
    for (const auto& q : params) {
        auto tex = props(q);
        tex->set(q.name, checker(q.a, q.b), SourceLocation{});
        auto m = MaterialRegistry::instance().create(*tex);
        auto ftex = FloatTextureRegistry::instance().create(*checker(q.a, q.b));
        for (vec2 uv : {vec2(0.25f, 0.25f), vec2(0.75f, 0.25f)}) {
            ShadingPoint sp;
            sp.tex.uv = uv;
            const float value = ftex->eval(sp.tex);
            auto constant = props(q);
            constant->set(q.name, value, SourceLocation{});
            auto mc = MaterialRegistry::instance().create(*constant);
            SampledWavelengths wl = SampledWavelengths::rgb(defaultChannelWavelengths());
            const BSDF* bt = m->getBSDF(sp, wl, arena);
            const BSDF* bc = mc->getBSDF(sp, wl, arena);
            for (float cl : {0.7f, -0.4f}) {
                const vec3 wo = dir(0.8f, 0.2f), wi = dir(cl, 2.7f);
                EXPECT_EQ(bt->eval(wo, wi, kRad)[0], bc->eval(wo, wi, kRad)[0]) << q.type << " " << q.name << " uv " << uv.x;
                EXPECT_EQ(bt->pdf(wo, wi, kRad), bc->pdf(wo, wi, kRad)) << q.type << " " << q.name;
            }
        }
    }
}

std::string writeScene(const std::string& name, const std::string& type, const std::string& params) {
    const auto dir = std::filesystem::temp_directory_path() / ("iris_principled_tests_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    const auto path = dir / name;
    std::ofstream(path) << "<scene version=\"3.0.0\">\n<bsdf type=\"" << type << "\">\n" << params << "\n</bsdf>\n</scene>\n";
    return path.string();
}

TEST(PrincipledMitsuba, BadInputIsAFileLineError) {
    struct Case {
        const char* type;
        const char* params;  // the offending parameter is on line 3 (last if several)
        const char* needle;
    };
    const std::vector<Case> cases = {
        {"principled", "<float name=\"eta\" value=\"1.4\"/>\n<float name=\"specular\" value=\"0.5\"/>", "either 'eta' or 'specular'"},
        {"principled", "<float name=\"metallic\" value=\"1.5\"/>", "'metallic' must be in [0, 1]"},
        {"principled", "<float name=\"spec_trans\" value=\"-0.1\"/>", "'spec_trans' must be in [0, 1]"},
        {"principled", "<float name=\"specular\" value=\"2\"/>", "'specular' must be in [0, 1]"},
        {"principled", "<float name=\"eta\" value=\"-1\"/>", "'eta' must be finite and > 0"},
        {"principled", "<float name=\"clearcoat_sampling_rate\" value=\"-1\"/>", "sampling rate"},
        {"principled", "<float name=\"subsurface\" value=\"0.5\"/>", "'disney'"},
        {"principledthin", "<float name=\"diff_trans\" value=\"2.5\"/>", "'diff_trans' must be in [0, 2]"},
        {"principledthin", "<float name=\"specular\" value=\"0.5\"/>", "no 'specular'"},
        {"principledthin", "<float name=\"clearcoat\" value=\"0.5\"/>", "unknown parameter 'clearcoat'"},
    };
    int i = 0;
    for (const auto& c : cases) {
        const std::string file = "bad_principled_" + std::to_string(i++) + ".xml";
        const int line = 3 + int(std::count(c.params, c.params + std::strlen(c.params), '\n'));
        try {
            loadScene(writeScene(file, c.type, c.params));
            ADD_FAILURE() << c.params << ": expected an iris::Error";
        } catch (const Error& e) {
            const std::string msg = e.what();
            EXPECT_NE(msg.find(file + ":" + std::to_string(line) + ":"), std::string::npos) << msg;
            EXPECT_NE(msg.find(c.needle), std::string::npos) << msg;
        }
    }
}

}  // namespace
}  // namespace iris
