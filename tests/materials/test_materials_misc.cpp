// phong, cook_torrance and twosided through the shared BSDF harness.
#include <gtest/gtest.h>

#include "core/rng.h"
#include "materials/fresnel.h"
#include "tests/support/bsdf_test_util.h"

using namespace iris;
using namespace iris::test;

TEST(MaterialsPhong, ChiSquareConsistencyEnergy) {
    const float exponents[] = {1.0f, 10.0f, 100.0f};
    const float cosines[] = {1.0f, 0.5f, 0.05f};
    Chi2Options opt;
    opt.samples = 300000;
    opt.numTests = int(std::size(exponents) * std::size(cosines));
    for (float e : exponents) {
        auto inst = makeBSDF("phong", {{"exponent", e}, {"diffuse_reflectance", 0.3f}, {"specular_reflectance", 0.7f}});
        for (float co : cosines) {
            const vec3 wo = dirFromCos(co, 0.5f);
            const auto r = chi2Test(*inst.bsdf, wo, opt);
            EXPECT_TRUE(r.passed) << e << " " << co << ": " << r.message;
            const auto k = checkConsistency(*inst.bsdf, wo, 5000);
            EXPECT_EQ(k.invalid, 0);
            EXPECT_LT(k.maxRelErrF, 1e-5f) << k.message;
            EXPECT_LT(k.maxRelErrPdf, 1e-5f) << k.message;
            const auto al = albedo(*inst.bsdf, wo, 100000);
            EXPECT_LT(al[0].mean, 1.0 + 4 * al[0].stderr_) << e << " " << co;
        }
        EXPECT_LT(reciprocityError(*inst.bsdf), 1e-4f);
    }
}

TEST(MaterialsPhong, NormalisedLobe) {
    // At normal incidence the specular lobe alone has albedo exactly ρs: ∫ (n+2)/(2π) cosⁿθ cosθ dω = 1.
    auto inst = makeBSDF("phong", {{"exponent", 20.0f}, {"diffuse_reflectance", 0.0f}, {"specular_reflectance", 1.0f}});
    const auto al = albedo(*inst.bsdf, dirFromCos(1.0f), 200000);
    EXPECT_NEAR(al[0].mean, 1.0, 4 * al[0].stderr_ + 1e-4);
    // Value at the mirror direction: (n+2)/(2π).
    const vec3 wo = dirFromCos(0.6f, 0.1f);
    EXPECT_NEAR(inst.bsdf->eval(wo, reflectLocal(wo), TransportMode::Radiance)[0], 22.0f * kInv2Pi, 1e-4f);
}

TEST(MaterialsCookTorrance, ChiSquareConsistency) {
    const float roughness[] = {0.05f, 0.3f, 0.8f};
    const float cosines[] = {1.0f, 0.5f, 0.05f};
    Chi2Options opt;
    opt.samples = 300000;
    opt.numTests = int(std::size(roughness) * std::size(cosines) * 2);
    for (bool visible : {true, false}) {
        for (float r : roughness) {
            auto inst = makeBSDF("cook_torrance", {{"roughness", r}, {"kd", 0.4f}, {"albedo", 0.6f}, {"f0", 0.04f}, {"sample_visible", visible}});
            for (float co : cosines) {
                const vec3 wo = dirFromCos(co, 0.5f);
                const auto res = chi2Test(*inst.bsdf, wo, opt);
                EXPECT_TRUE(res.passed) << r << " " << co << ": " << res.message;
                const auto k = checkConsistency(*inst.bsdf, wo, 5000);
                EXPECT_EQ(k.invalid, 0);
                EXPECT_LT(k.maxRelErrF, 1e-4f) << k.message;
                EXPECT_LT(k.maxRelErrPdf, 1e-4f) << k.message;
            }
            EXPECT_LT(reciprocityError(*inst.bsdf), 1e-4f);
        }
    }
}

TEST(MaterialsCookTorrance, MatchesThesisFormula) {
    // f = kd·albedo/π + (1−kd)·D F G / (4 (n·l)(n·v)) with Beckmann D (thesis 003 §4.12 form
    // exp(((n·h)²−1)/(r²(n·h)²)) / (π r² (n·h)⁴)), Schlick F and the V-cavity G.
    const float r = 0.3f, kd = 0.4f, albedoV = 0.6f, f0 = 0.04f;
    auto inst = makeBSDF("cook_torrance", {{"roughness", r}, {"kd", kd}, {"albedo", albedoV}, {"f0", f0}});
    const vec3 v = dirFromCos(0.8f, 0.0f), l = dirFromCos(0.6f, 2.5f);
    const vec3 h = glm::normalize(v + l);
    const float nh = h.z;
    const float D = std::exp((nh * nh - 1) / (r * r * nh * nh)) / (kPi * r * r * nh * nh * nh * nh);
    const float F = f0 + (1 - f0) * std::pow(1 - glm::dot(l, h), 5.0f);
    const float G = std::min(1.0f, std::min(2 * nh * v.z / glm::dot(h, v), 2 * nh * l.z / glm::dot(h, v)));
    const float expect = kd * albedoV / kPi + (1 - kd) * D * F * G / (4 * l.z * v.z);
    EXPECT_NEAR(inst.bsdf->eval(v, l, TransportMode::Radiance)[1], expect, 1e-5f * expect);
    EXPECT_THROW(makeBSDF("cook_torrance", {{"kd", 1.5f}}), Error);
}

TEST(MaterialsTwoSided, FlipsToTheUpperSide) {
    auto one = makeBSDF("diffuse", {{"reflectance", 0.5f}});
    auto props = makeProps("twosided", {});
    props->addChild(makeProps("diffuse", {{"reflectance", 0.5f}}));
    auto two = makeBSDF(*props, SampledWavelengths::rgb(defaultChannelWavelengths()));
    const vec3 wo = dirFromCos(0.6f, 0.3f), wi = dirFromCos(0.3f, 2.0f);
    const auto flip = [](const vec3& w) { return vec3(w.x, w.y, -w.z); };
    EXPECT_EQ(one.bsdf->eval(flip(wo), flip(wi), TransportMode::Radiance)[0], 0.0f);
    EXPECT_NEAR(two.bsdf->eval(flip(wo), flip(wi), TransportMode::Radiance)[0], 0.5f / kPi, 1e-6f);
    EXPECT_NEAR(two.bsdf->eval(wo, wi, TransportMode::Radiance)[0], 0.5f / kPi, 1e-6f);
    EXPECT_EQ(two.bsdf->eval(flip(wo), wi, TransportMode::Radiance)[0], 0.0f);
    Chi2Options opt;
    opt.numTests = 2;
    for (float co : {0.7f, -0.7f}) {
        const vec3 w = dirFromCos(co, 0.2f);
        const auto r = chi2Test(*two.bsdf, w, opt);
        EXPECT_TRUE(r.passed) << r.message;
        const auto k = checkConsistency(*two.bsdf, w, 5000);
        EXPECT_LT(k.maxRelErrF, 1e-6f);
        EXPECT_LT(k.maxRelErrPdf, 1e-6f);
    }
}

TEST(MaterialsTwoSided, FrontAndBack) {
    auto props = makeProps("twosided", {});
    props->addChild(makeProps("diffuse", {{"reflectance", 0.2f}}));
    props->addChild(makeProps("roughconductor", {{"alpha", 0.3f}}));
    auto two = makeBSDF(*props, SampledWavelengths::rgb(defaultChannelWavelengths()));
    EXPECT_NEAR(albedo(*two.bsdf, dirFromCos(0.5f), 20000)[0].mean, 0.2, 1e-5);
    const auto back = albedo(*two.bsdf, dirFromCos(-0.5f), 20000);
    EXPECT_GT(back[0].mean, 0.8);  // the mirror-like back
    EXPECT_TRUE(two.bsdf->flags() & kBSDFGlossy);
    EXPECT_TRUE(two.bsdf->flags() & kBSDFDiffuse);

    auto none = makeProps("twosided", {});
    EXPECT_THROW(makeBSDF(*none, SampledWavelengths::rgb(defaultChannelWavelengths())), Error);
    auto three = makeProps("twosided", {});
    for (int i = 0; i < 3; ++i) three->addChild(makeProps("diffuse", {}));
    EXPECT_THROW(makeBSDF(*three, SampledWavelengths::rgb(defaultChannelWavelengths())), Error);
    // A named nested bsdf works too.
    auto named = makeProps("twosided", {{"bsdf", makeProps("diffuse", {{"reflectance", 0.3f}})}});
    auto n = makeBSDF(*named, SampledWavelengths::rgb(defaultChannelWavelengths()));
    EXPECT_NEAR(albedo(*n.bsdf, dirFromCos(-0.5f), 1000)[0].mean, 0.3, 1e-5);
}

TEST(MaterialsAll, SpectralAndRGBModes) {
    // Every core material works with any number of wavelengths and in RGB mode: finite,
    // non-negative weights, and (non-specular ones) chi-square + consistency at one angle.
    const std::vector<std::pair<std::string, std::shared_ptr<Properties>>> mats = {
        {"phong", makeProps("phong", {{"exponent", 20.0f}})},
        {"cook_torrance", makeProps("cook_torrance", {{"roughness", 0.3f}})},
        {"conductor", makeProps("conductor", {{"material", std::string("Au")}})},
        {"roughconductor", makeProps("roughconductor", {{"material", std::string("Cu")}, {"alpha", 0.3f}})},
        {"dielectric", makeProps("dielectric", {{"int_sellmeier_b", VectorValue{vec3(1.03961212f, 0.231792344f, 1.01046945f)}},
                                                {"int_sellmeier_c", VectorValue{vec3(0.00600069867f, 0.0200179144f, 103.560653f)}}})},
        {"roughdielectric", makeProps("roughdielectric", {{"int_cauchy_a", 1.5f}, {"int_cauchy_b", 0.004f}, {"alpha", 0.3f},
                                                          {"distribution", std::string("ggx")}})},
        {"thindielectric", makeProps("thindielectric", {{"int_ior", std::string("pyrex")}})},
    };
    Chi2Options opt;
    opt.samples = 200000;
    opt.numTests = int(mats.size()) * 3;
    for (const auto& [name, props] : mats) {
        for (int n : {0, 1, 8}) {
            const SampledWavelengths wl = n == 0 ? SampledWavelengths::rgb(defaultChannelWavelengths()) : SampledWavelengths::sampleVisible(0.61f, n);
            auto inst = makeBSDF(*props, wl);
            ASSERT_NE(inst.bsdf, nullptr) << name;
            const vec3 wo = dirFromCos(0.6f, 0.3f);
            Sampler rng(5, 6, 7);
            for (int i = 0; i < 2000; ++i) {
                const float uc = rng.get1D();
                const auto s = inst.bsdf->sample(wo, uc, rng.get2D(), TransportMode::Radiance);
                if (!s) continue;
                ASSERT_EQ(s->f.size(), wl.size()) << name;
                ASSERT_FALSE(s->f.hasNonFinite()) << name << " n " << n;
                ASSERT_FALSE(s->f.hasNegative()) << name << " n " << n;
            }
            if (inst.bsdf->hasNonSpecular()) {
                const auto r = chi2Test(*inst.bsdf, wo, opt);
                EXPECT_TRUE(r.passed) << name << " n " << n << ": " << r.message;
                const auto k = checkConsistency(*inst.bsdf, wo, 3000);
                EXPECT_LT(k.maxRelErrF, 1e-3f) << name << " n " << n << ": " << k.message;
                EXPECT_LT(k.maxRelErrPdf, 1e-3f) << name << " n " << n << ": " << k.message;
            }
        }
    }
}
