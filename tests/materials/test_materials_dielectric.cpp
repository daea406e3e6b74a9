// dielectric, thindielectric and roughdielectric through the shared BSDF harness, plus IOR
// presets and dispersion.
#include <gtest/gtest.h>

#include "spectral/ior.h"
#include "spectral/ior_presets.h"
#include "materials/fresnel.h"
#include "tests/support/bsdf_test_util.h"

using namespace iris;
using namespace iris::test;

namespace {
const SampledWavelengths kRGB = SampledWavelengths::rgb(defaultChannelWavelengths());

/// Probability and weight of each delta lobe of a specular BSDF, found by scanning uc.
struct Lobes {
    float pR = 0, pT = 0;
    SampledSpectrum wR, wT;
    vec3 wiR{0.f}, wiT{0.f};
};
Lobes specularLobes(const BSDF& b, const vec3& wo, TransportMode mode = TransportMode::Radiance) {
    Lobes l;
    for (int i = 0; i < 1000; ++i) {
        const auto s = b.sample(wo, (i + 0.5f) / 1000, vec2(0.5f), mode);
        if (!s) continue;
        if (s->isTransmission()) {
            l.pT = s->pdf;
            l.wT = s->weight();
            l.wiT = s->wi;
        } else {
            l.pR = s->pdf;
            l.wR = s->weight();
            l.wiR = s->wi;
        }
    }
    return l;
}
}  // namespace

TEST(MaterialsDielectric, IORPresetsAndForms) {
    float eta = 0;
    ASSERT_TRUE(lookupIORPreset("water", &eta));
    EXPECT_FLOAT_EQ(eta, 1.333f);
    ASSERT_TRUE(lookupIORPreset("bk7", &eta));
    EXPECT_FLOAT_EQ(eta, 1.5046f);
    ASSERT_TRUE(lookupIORPreset("diamond", &eta));
    EXPECT_FLOAT_EQ(eta, 2.419f);
    EXPECT_FALSE(lookupIORPreset("unobtainium", &eta));
    EXPECT_EQ(iorPresetNames().size(), 23u);

    // Cauchy (BK7-like A = 1.5046, B = 0.00420 µm²) and Sellmeier (Schott BK7 coefficients).
    const IOR cauchy = IOR::cauchy(1.5046f, 0.00420f);
    EXPECT_NEAR(cauchy.eval(500.0f), 1.5046f + 0.0042f / 0.25f, 1e-6f);
    EXPECT_TRUE(cauchy.isDispersive());
    const IOR bk7 = IOR::sellmeier(vec3(1.03961212f, 0.231792344f, 1.01046945f), vec3(0.00600069867f, 0.0200179144f, 103.560653f));
    EXPECT_NEAR(bk7.eval(587.6f), 1.5168f, 2e-4f);  // BK7 n_d
    EXPECT_GT(bk7.eval(450.0f), bk7.eval(650.0f));  // normal dispersion

    // Per-channel: exact in RGB mode, piecewise linear with constant extrapolation in spectral mode.
    const IOR pc = IOR::perChannel(vec3(1.5f, 1.6f, 1.8f));
    const SampledSpectrum s = pc.sample(kRGB);
    EXPECT_EQ(s[0], 1.5f);
    EXPECT_EQ(s[1], 1.6f);
    EXPECT_EQ(s[2], 1.8f);
    EXPECT_FLOAT_EQ(pc.eval(400.0f), 1.8f);
    EXPECT_FLOAT_EQ(pc.eval(700.0f), 1.5f);
    EXPECT_FLOAT_EQ(pc.eval(585.0f), 1.55f);
    EXPECT_FLOAT_EQ(pc.eval(485.0f), 1.7f);
    // Even with other RGB channel wavelengths the three values come back exactly.
    const SampledSpectrum s2 = pc.sample(SampledWavelengths::rgb(vec3(680, 520, 400)));
    EXPECT_EQ(s2[0], 1.5f);
    EXPECT_EQ(s2[2], 1.8f);
}

TEST(MaterialsDielectric, IORParameters) {
    auto named = makeBSDF("dielectric", {{"int_ior", std::string("water")}, {"ext_ior", std::string("vacuum")}});
    const vec3 wo = dirFromCos(1.0f);
    EXPECT_NEAR(specularLobes(*named.bsdf, wo).pR, schlickF0FromEta(1.333f), 1e-6f);
    auto number = makeBSDF("dielectric", {{"int_ior", 2.0f}, {"ext_ior", 1.0f}});
    EXPECT_NEAR(specularLobes(*number.bsdf, wo).pR, schlickF0FromEta(2.0f), 1e-6f);
    EXPECT_THROW(makeBSDF("dielectric", {{"int_ior", std::string("glassy")}}), Error);
    EXPECT_THROW(makeBSDF("dielectric", {{"int_ior", 1.5f}, {"int_cauchy_a", 1.5f}}), Error);
    EXPECT_THROW(makeBSDF("dielectric", {{"intior", 1.5f}}), Error);
    // rgb η: per-channel, exact in RGB mode.
    auto rgb = makeBSDF("dielectric", {{"int_ior", RGBValue{vec3(1.5f, 1.6f, 1.8f)}}, {"ext_ior", 1.0f}});
    const Lobes l = specularLobes(*rgb.bsdf, wo);
    // Lobe value F_c per channel = weight × probability; the green channel decides the probability.
    EXPECT_NEAR(l.wR[0] * l.pR, schlickF0FromEta(1.5f), 1e-6f);
    EXPECT_NEAR(l.wR[1] * l.pR, schlickF0FromEta(1.6f), 1e-6f);
    EXPECT_NEAR(l.wR[2] * l.pR, schlickF0FromEta(1.8f), 1e-6f);
    EXPECT_NEAR(l.pR, schlickF0FromEta(1.6f), 1e-6f);
}

TEST(MaterialsDielectric, DispersionTerminatesSecondaryWavelengths) {
    const SampledWavelengths wl = SampledWavelengths::sampleVisible(0.42f, 4);
    auto disp = makeBSDF("dielectric", {{"int_cauchy_a", 1.5f}, {"int_cauchy_b", 0.01f}}, wl);
    EXPECT_TRUE(disp.wl.secondaryTerminated());
    auto plain = makeBSDF("dielectric", {{"int_ior", 1.5f}}, wl);
    EXPECT_FALSE(plain.wl.secondaryTerminated());
    auto rough = makeBSDF("roughdielectric", {{"int_ior", RGBValue{vec3(1.5f, 1.6f, 1.8f)}}}, wl);
    EXPECT_TRUE(rough.wl.secondaryTerminated());
    auto rgbMode = makeBSDF("dielectric", {{"int_cauchy_a", 1.5f}, {"int_cauchy_b", 0.01f}});
    EXPECT_FALSE(rgbMode.wl.secondaryTerminated());
}

TEST(MaterialsDielectric, SmoothReflectionRefraction) {
    const float eta = 1.5f;
    auto inst = makeBSDF("dielectric", {{"int_ior", eta}, {"ext_ior", 1.0f}});
    for (float co : {1.0f, 0.7f, 0.2f, 0.05f, -0.9f, -0.5f, -0.3f}) {
        const vec3 wo = dirFromCos(co, 0.4f);
        const Lobes l = specularLobes(*inst.bsdf, wo);
        const auto fr = fresnelDielectricFull(co, eta);
        EXPECT_NEAR(l.pR, fr.R, 1e-6f) << co;
        EXPECT_NEAR(l.pR + l.pT, 1.0f, 1e-6f) << co;
        EXPECT_NEAR(glm::length(l.wiR - reflectLocal(wo)), 0.0f, 1e-6f);
        if (fr.R < 1.0f) {
            // Snell's law and the radiance scaling (η_i/η_t)² of the transmitted weight.
            const float etaI = co > 0 ? 1.0f : eta, etaT = co > 0 ? eta : 1.0f;
            EXPECT_NEAR(etaI * sinTheta(wo), etaT * sinTheta(l.wiT), 1e-5f) << co;
            EXPECT_LT(l.wiT.z * wo.z, 0.0f);
            EXPECT_NEAR(l.wT[1], sqr(etaI / etaT), 1e-5f) << co;
            const Lobes imp = specularLobes(*inst.bsdf, wo, TransportMode::Importance);
            EXPECT_NEAR(imp.wT[1], 1.0f, 1e-5f) << co;
        } else {
            EXPECT_EQ(l.pT, 0.0f) << "total internal reflection at " << co;
        }
        EXPECT_NEAR(l.wR[1], 1.0f, 1e-5f);  // reflection weight F/pdf = 1
    }
}

TEST(MaterialsDielectric, ThinDielectric) {
    const float eta = 1.5f;
    auto inst = makeBSDF("thindielectric", {{"int_ior", eta}, {"ext_ior", 1.0f}});
    for (float co : {1.0f, 0.5f, 0.1f, -0.6f}) {
        const vec3 wo = dirFromCos(co, 1.0f);
        const Lobes l = specularLobes(*inst.bsdf, wo);
        const float R = fresnelDielectric(std::abs(co), eta), T = 1 - R;
        const float R2 = R + T * T * R / (1 - R * R);
        EXPECT_NEAR(l.pR, R2, 1e-6f);
        EXPECT_NEAR(l.pT, 1 - R2, 1e-6f);
        EXPECT_NEAR(glm::length(l.wiT + wo), 0.0f, 1e-7f);  // straight through
        EXPECT_NEAR(l.wR[0], 1.0f, 1e-5f);
        EXPECT_NEAR(l.wT[0], 1.0f, 1e-5f);
        const auto al = albedo(*inst.bsdf, wo, 10000);
        EXPECT_NEAR(al[0].mean, 1.0, 1e-5);  // lossless sheet
    }
}

TEST(MaterialsDielectric, RoughChiSquareConsistency) {
    struct Case {
        const char* dist;
        float au, av;
        bool visible;
    };
    std::vector<Case> cases;
    for (const char* dist : {"beckmann", "ggx"})
        for (float a : {0.05f, 0.3f, 0.8f}) cases.push_back({dist, a, a, true});
    cases.push_back({"ggx", 0.3f, 0.3f, false});
    cases.push_back({"beckmann", 0.3f, 0.3f, false});
    cases.push_back({"ggx", 0.1f, 0.5f, true});
    const float cosines[] = {1.0f, 0.5f, 0.05f, -0.9f, -0.5f, -0.05f};
    Chi2Options opt;
    opt.samples = 300000;
    opt.numTests = int(cases.size() * std::size(cosines));
    for (const Case& c : cases) {
        auto props = makeProps("roughdielectric",
                               {{"distribution", std::string(c.dist)}, {"int_ior", 1.5f}, {"ext_ior", 1.0f}, {"sample_visible", c.visible}});
        if (c.au == c.av) {
            props->set("alpha", c.au, {});
        } else {
            props->set("alpha_u", c.au, {});
            props->set("alpha_v", c.av, {});
        }
        auto inst = makeBSDF(*props, kRGB);
        const std::string label = strCat(c.dist, " ", c.au, "/", c.av, c.visible ? " visible" : " all");
        for (float co : cosines) {
            const vec3 wo = dirFromCos(co, 0.7f);
            const auto r = chi2Test(*inst.bsdf, wo, opt);
            EXPECT_TRUE(r.passed) << label << " cos " << co << ": " << r.message;
            const auto k = checkConsistency(*inst.bsdf, wo, 5000);
            EXPECT_EQ(k.invalid, 0) << label;
            EXPECT_LT(k.maxRelErrF, 1e-3f) << label << " cos " << co << ": " << k.message;
            EXPECT_LT(k.maxRelErrPdf, 1e-3f) << label << " cos " << co << ": " << k.message;
            // Energy: the adjoint (Importance) BSDF conserves energy from both sides; the radiance
            // BSDF from outside (from inside it carries the η² radiance gain).
            const auto ai = albedo(*inst.bsdf, wo, 50000, 7, TransportMode::Importance);
            EXPECT_LT(ai[1].mean, 1.0 + 4 * ai[1].stderr_) << label << " cos " << co;
            if (co > 0) {
                const auto ar = albedo(*inst.bsdf, wo, 50000, 8);
                EXPECT_LT(ar[1].mean, 1.0 + 4 * ar[1].stderr_) << label << " cos " << co;
            }
        }
        EXPECT_LT(reciprocityError(*inst.bsdf), 1e-3f) << label;
    }
}

TEST(MaterialsDielectric, RoughTransmissionGeneralisedReciprocity) {
    // Radiance BTDF: f(wo, wi)/η_o² = f(wi, wo)/η_i² (Veach 1997 eq. 5.14).
    const float eta = 1.5f;
    auto inst = makeBSDF("roughdielectric", {{"alpha", 0.4f}, {"int_ior", eta}, {"ext_ior", 1.0f}, {"distribution", std::string("ggx")}});
    int checked = 0;
    for (int i = 0; i < 200; ++i) {
        const vec3 wo = dirFromCos(0.1f + 0.9f * (i % 10) / 10.0f, 0.3f * i);
        const vec3 wi = -dirFromCos(0.1f + 0.9f * ((i / 10) % 10) / 10.0f, 1.0f + 0.7f * i);
        const float a = inst.bsdf->eval(wo, wi, TransportMode::Radiance)[1];
        const float b = inst.bsdf->eval(wi, wo, TransportMode::Radiance)[1];
        if (a < 1e-4f) continue;
        ++checked;
        // wo outside (η_o = 1), wi inside (η_i = η).
        EXPECT_NEAR(a, b / (eta * eta), 1e-3f * a);
    }
    EXPECT_GT(checked, 30);
}

TEST(MaterialsDielectric, RoughApproachesSmoothAsAlphaVanishes) {
    auto smooth = makeBSDF("dielectric", {{"int_ior", 1.5f}, {"ext_ior", 1.0f}});
    for (const char* dist : {"beckmann", "ggx"}) {
        auto rough = makeBSDF("roughdielectric", {{"int_ior", 1.5f}, {"ext_ior", 1.0f}, {"alpha", 1e-4f}, {"distribution", std::string(dist)}});
        for (float co : {1.0f, 0.7f, 0.3f, -0.95f, -0.8f}) {
            const vec3 wo = dirFromCos(co, 0.2f);
            const Lobes l = specularLobes(*smooth.bsdf, wo);
            const auto [r, t] = albedoSplit(*rough.bsdf, wo, 1, 20000);
            EXPECT_NEAR(r.mean, l.pR, 2e-3 + 4 * r.stderr_) << dist << " " << co;
            EXPECT_NEAR(t.mean, l.pT * l.wT[1], 2e-3 + 4 * t.stderr_) << dist << " " << co;
        }
    }
}
