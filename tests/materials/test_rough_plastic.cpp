// plastic and roughplastic (Jakob; thesis 000 §2.5): sampling (χ², consistency), white furnace,
// the diffuse energy predicted by the model, and the α → 0 limit (rough plastic → plastic).
#include <gtest/gtest.h>

#include "core/rng.h"
#include "materials/fresnel.h"
#include "materials/rough_plastic_tables.h"
#include "tests/support/bsdf_test_util.h"

using namespace iris;
using namespace iris::test;

TEST(RoughPlastic, SamplingMatchesPdfChi2) {
    struct Case {
        const char* dist;
        float alpha, cosO;
    };
    const Case cases[] = {{"beckmann", 0.1f, 0.8f}, {"beckmann", 0.5f, 0.3f}, {"ggx", 0.2f, 0.6f},
                          {"ggx", 0.8f, 0.1f},      {"beckmann", 0.05f, 0.95f}, {"ggx", 0.3f, 0.5f}};
    Chi2Options opt;
    opt.numTests = 6;
    for (const Case& k : cases) {
        // The last case samples all normals (sample_visible false, Mitsuba's parameter).
        const bool visible = &k != &cases[5];
        auto inst = makeBSDF("roughplastic", {{"distribution", std::string(k.dist)},
                                              {"alpha", k.alpha},
                                              {"sample_visible", visible},
                                              {"diffuse_reflectance", RGBValue{vec3(0.8f, 0.4f, 0.1f)}}});
        const vec3 wo = dirFromCos(k.cosO, 0.4f);
        const Chi2Result r = chi2Test(*inst.bsdf, wo, opt);
        EXPECT_TRUE(r.passed) << k.dist << " alpha " << k.alpha << ": " << r.message;
        const ConsistencyResult c = checkConsistency(*inst.bsdf, wo);
        EXPECT_EQ(c.invalid, 0) << c.message;
        EXPECT_LT(c.maxRelErrF, 1e-5f);
        EXPECT_LT(c.maxRelErrPdf, 1e-5f);
    }
}

TEST(RoughPlastic, WhiteFurnaceAtMostOne) {
    // Both versions' models (docs/scene_format.md). Mitsuba 3's darkens the base more at large α
    // (R_int excludes the interface's single-scattering loss), down to 0.19 at grazing α = 0.9.
    for (int version : {0, 3})
    for (const char* dist : {"beckmann", "ggx"})
        for (float alpha : {0.02f, 0.2f, 0.9f})
            for (bool nonlinear : {false, true}) {
                auto inst = makeBSDFVersion(version, "roughplastic", {{"distribution", std::string(dist)},
                                                                      {"alpha", alpha},
                                                                      {"diffuse_reflectance", 1.0f},
                                                                      {"nonlinear", nonlinear}});
                for (float c : {0.05f, 0.4f, 1.0f}) {
                    const auto a = albedo(*inst.bsdf, dirFromCos(c), 40000);
                    EXPECT_LE(a[0].mean, 1.0 + 5 * a[0].stderr_) << dist << " alpha " << alpha << " cos " << c;
                    // single-scattering loss is large only at grazing α = 0.9
                    EXPECT_GT(a[0].mean, version == 0 ? 0.3 : 0.15) << version << " " << dist << " " << alpha << " " << c;
                }
            }
}

TEST(RoughPlastic, DiffuseAlbedoMatchesModel) {
    // ks = 0: the albedo is ρ' T12(μo) Td, with Td = (1/η²) 2∫T μ dμ (eq. 2.55 integrated):
    // nonlinear ρ' = ρ/(1 − ρ Fdr) gives ρ T12 Td/(1 − ρ(1 − Td)) with Mitsuba 0.6's Fdr = 1 − Td
    // (version 0.x; Mitsuba 3's: test_rough_plastic_mitsuba3.cpp).
    const float eta = 1.49f / 1.000277f, rho = 0.7f, alpha = 0.3f;
    auto inst = makeBSDFVersion(0, "roughplastic", {{"alpha", alpha},
                                          {"specular_reflectance", 0.0f},
                                          {"diffuse_reflectance", rho},
                                          {"nonlinear", true}});
    const RoughTransmittanceTables& t = roughPlasticTables(MicrofacetType::Beckmann);
    const double td = roughInternalDiffuseIntegral(MicrofacetType::Beckmann, eta, alpha, 24, 32);
    for (float c : {0.2f, 0.7f}) {
        const auto a = albedo(*inst.bsdf, dirFromCos(c), 200000);
        const double expected = rho * t.transmittance(eta, alpha, c) * td / (1.0 - rho * (1.0 - td));
        EXPECT_NEAR(a[0].mean, expected, 5 * a[0].stderr_ + 2e-3) << "cos " << c;
    }
}

TEST(Plastic, WhiteFurnaceIsExactlyOne) {
    // Smooth coat, ρ = ks = 1: F + (1 − F)·Td/(1 − Fdr) = 1 exactly (both normalisations).
    for (bool nonlinear : {false, true}) {
        auto inst = makeBSDF("plastic", {{"diffuse_reflectance", 1.0f}, {"nonlinear", nonlinear}});
        for (float c : {0.1f, 0.5f, 0.95f}) {
            const auto a = albedo(*inst.bsdf, dirFromCos(c), 200000);
            EXPECT_NEAR(a[0].mean, 1.0, 5 * a[0].stderr_ + 2e-4) << "cos " << c;
        }
    }
}

TEST(Plastic, DiffuseSamplingAndDeltaLobe) {
    auto inst = makeBSDF("plastic", {{"diffuse_reflectance", RGBValue{vec3(0.2f, 0.5f, 0.9f)}}});
    const vec3 wo = dirFromCos(0.6f, 1.0f);
    const ConsistencyResult c = checkConsistency(*inst.bsdf, wo);
    EXPECT_EQ(c.invalid, 0) << c.message;
    EXPECT_GT(c.specular, 0);
    EXPECT_GT(c.nonSpecular, 0);
    EXPECT_LT(c.maxRelErrPdf, 1e-5f);
    // Delta lobe: mirror direction, f·cos/pdf = F / P(spec).
    auto s = inst.bsdf->sample(wo, 0.0f, vec2(0.5f), TransportMode::Radiance);
    ASSERT_TRUE(s && s->isSpecular());
    EXPECT_NEAR(s->wi.x, -wo.x, 1e-6f);
    EXPECT_NEAR(s->wi.z, wo.z, 1e-6f);
    EXPECT_NEAR(s->f[0] * s->wi.z, fresnelDielectric(0.6f, 1.49f / 1.000277f), 1e-6f);
    const Estimate p = pdfIntegral(*inst.bsdf, wo);
    EXPECT_LT(p.mean, 1.0);  // the continuous part has mass 1 − P(spec)
}

TEST(RoughPlastic, ApproachesPlasticAsAlphaGoesToZero) {
    // Directional albedo of roughplastic with α = 0.002 against plastic, per channel. Mitsuba 0.6's
    // roughplastic (Fdr = 1 − Td → the smooth Fdr); Mitsuba 3's takes the mean over 64 nodes of
    // the internal reflectance instead, 1.5 % below the smooth integral at η = 1.49.
    const vec3 rho(0.8f, 0.4f, 0.1f);
    for (const char* dist : {"beckmann", "ggx"}) {
        auto rough = makeBSDFVersion(0, "roughplastic", {{"distribution", std::string(dist)},
                                               {"alpha", 0.002f},
                                               {"diffuse_reflectance", RGBValue{rho}}});
        auto smooth = makeBSDF("plastic", {{"diffuse_reflectance", RGBValue{rho}}});
        for (float c : {0.3f, 0.6f, 0.95f}) {
            const auto ar = albedo(*rough.bsdf, dirFromCos(c), 200000);
            const auto as = albedo(*smooth.bsdf, dirFromCos(c), 200000);
            for (int k = 0; k < 3; ++k)
                EXPECT_NEAR(ar[k].mean, as[k].mean, 5 * (ar[k].stderr_ + as[k].stderr_) + 3e-3)
                    << dist << " cos " << c << " channel " << k;
        }
    }
}

TEST(RoughPlastic, RejectsBadParameters) {
    EXPECT_THROW(makeBSDF("roughplastic", {{"distribution", std::string("phong")}}), Error);
    EXPECT_THROW(makeBSDF("roughplastic", {{"alpha", 1.5f}}), Error);
    EXPECT_THROW(makeBSDF("roughplastic", {{"int_ior", 0.9f}}), Error);
    EXPECT_THROW(makeBSDF("plastic", {{"int_ior", -1.0f}}), Error);
}

TEST(RoughPlastic, NearlyIndexMatchedCoatAtGrazingConservesEnergy) {
    // η → 1⁺ at grazing: specular F → 1 and the table's T(μo → 0) must go to 0 as well.
    for (const char* dist : {"beckmann", "ggx"}) {
        auto inst = makeBSDF("roughplastic", {{"distribution", std::string(dist)},
                                              {"alpha", 1e-4f},
                                              {"int_ior", 1.0001f},
                                              {"ext_ior", 1.0f},
                                              {"diffuse_reflectance", 1.0f}});
        for (float c : {0.0002f, 0.002f, 0.05f}) {
            const auto a = albedo(*inst.bsdf, dirFromCos(c), 100000);
            EXPECT_LE(a[0].mean, 1.0 + 5 * a[0].stderr_ + 0.01) << dist << " cos " << c;
        }
    }
}

TEST(RoughPlastic, CollapsedLineMatchesGeneralTablePath) {
    // Constant α reads one collapsed μ-line per material; a checkerboard α with equal colours is
    // the same α through the general (η, α) stencil. eval and pdf agree up to float rounding in
    // version 0.6; in version 3 the textured α also reads Mitsuba 3's R_int from a curve over the
    // α nodes (Mitsuba3InternalReflectanceCurve, ≤ 2e-4 from the direct value, i.e. ≤ 1e-3 in f).
    for (int version : {0, 3})
    for (const char* dist : {"beckmann", "ggx"})
        for (float alpha : {0.0f, 0.1f, 0.7f, 1.0f})
            for (float ior : {1.05f, 1.49f, 2.5f}) {
                const float tol = version == 0 ? 2e-5f : 1e-3f;
                auto checker = std::make_shared<Properties>("texture", "checkerboard", SourceLocation{"<test>", 0});
                checker->set("color0", alpha, SourceLocation{"<test>", 0});
                checker->set("color1", alpha, SourceLocation{"<test>", 0});
                auto fast = makeBSDFVersion(version, "roughplastic",
                                            {{"distribution", std::string(dist)}, {"alpha", alpha}, {"int_ior", ior}});
                auto general = makeBSDFVersion(version, "roughplastic",
                                               {{"distribution", std::string(dist)}, {"alpha", PropertyValue(checker)}, {"int_ior", ior}});
                Pcg32 rng(5, 9);
                for (int i = 0; i < 300; ++i) {
                    const vec3 wo = dirFromCos(0.01f + 0.99f * rng.uniform(), 6.28f * rng.uniform());
                    const vec3 wi = dirFromCos(0.01f + 0.99f * rng.uniform(), 6.28f * rng.uniform());
                    const SampledSpectrum a = fast.bsdf->eval(wo, wi, TransportMode::Radiance);
                    const SampledSpectrum b = general.bsdf->eval(wo, wi, TransportMode::Radiance);
                    for (int c = 0; c < 3; ++c)
                        EXPECT_NEAR(a[c], b[c], tol * std::max(1.0f, b[c])) << version << " " << dist << " " << alpha;
                    const float pa = fast.bsdf->pdf(wo, wi, TransportMode::Radiance);
                    const float pb = general.bsdf->pdf(wo, wi, TransportMode::Radiance);
                    EXPECT_NEAR(pa, pb, 2e-5f * std::max(1.0f, pb));
                }
            }
}
