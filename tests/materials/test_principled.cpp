// Tests of the Disney principled BRDF (materials/principled.cpp): Burley's published terms,
// reductions (metallic = 1 has no diffuse lobe; the all-zero configuration is Burley diffuse),
// spectral tint luminance, GTR1 normalisation, chi-square sampling tests at several roughness /
// anisotropy / clear-coat settings and grazing angles, eval/pdf consistency, reciprocity, white
// furnace bounds, and the measured albedo table of docs/materials_principled_cloth.md.
#include <cstdio>

#include <gtest/gtest.h>

#include "core/error.h"
#include "core/registry.h"
#include "materials/microfacet.h"
#include "materials/principled_terms.h"
#include "spectral/spectrum_factory.h"
#include "tests/support/bsdf_test_util.h"

namespace iris {
namespace {

using test::makeBSDF;
constexpr TransportMode kRad = TransportMode::Radiance;

TEST(PrincipledTerms, GTR1IsNormalised) {
    for (float alpha : {0.001f, 0.01f, 0.1f, 0.5f, 0.9f, 1.0f}) {
        // ∫ D cosθh dω = 2π ∫ D(θ) cosθ sinθ dθ = π ∫_0^1 D(√x) dx with x = cos²θh; the peak at
        // x = 1 has width ~α², so integrate in t = ln(1 − x) (dx = (1 − x) dt), midpoint rule.
        const int n = 200000;
        const double t0 = std::log(1e-14), dt = -t0 / n;
        double sum = 0;
        for (int i = 0; i < n; ++i) {
            const double y = std::exp(t0 + (i + 0.5) * dt);  // y = 1 − x
            sum += principled::gtr1D(float(std::sqrt(1.0 - y)), alpha) * y * dt;
        }
        EXPECT_NEAR(M_PI * sum, 1.0, 2e-3) << "alpha " << alpha;
    }
}

TEST(PrincipledTerms, SubsurfaceUsesSumOfCosines) {
    // cosθl = cosθv = 0.5, cosθd = 1, roughness 1: F_ss90 = 1 so F_ss = 1 and
    // ss = 1.25 (1/(0.5 + 0.5) − 0.5 + 0.5) = 1.25 (thesis 003's 1/(cosθl cosθv) would give 5).
    EXPECT_FLOAT_EQ(principled::subsurfaceFactor(0.5f, 0.5f, 1.0f, 1.0f), 1.25f);
    // At grazing light with roughness 0, F_ss90 = 0 and F_ss → 0 so ss → 1.25 · 0.5.
    EXPECT_NEAR(principled::subsurfaceFactor(1e-6f, 1.0f, 0.7f, 0.0f), 0.625f, 1e-4f);
    // Burley diffuse: F_D90 = 0.5 + 2 r cos²θd; at grazing light, cosθv = 1: factor = F_D90.
    EXPECT_NEAR(principled::burleyDiffuseFactor(0.0f, 1.0f, 0.8f, 1.0f), 0.5f + 2.0f * 0.64f, 1e-6f);
    EXPECT_NEAR(principled::burleyDiffuseFactor(0.0f, 1.0f, 0.8f, 0.0f), 0.5f, 1e-6f);
}

TEST(PrincipledTerms, AnisotropicAlphas) {
    const vec2 a = principled::anisotropicAlphas(0.5f, 0.0f);
    EXPECT_FLOAT_EQ(a.x, 0.25f);
    EXPECT_FLOAT_EQ(a.y, 0.25f);
    const vec2 b = principled::anisotropicAlphas(0.5f, 1.0f);
    EXPECT_NEAR(b.x, 0.25f / std::sqrt(0.1f), 1e-6f);
    EXPECT_NEAR(b.y, 0.25f * std::sqrt(0.1f), 1e-6f);
    EXPECT_FLOAT_EQ(principled::clearcoatAlpha(0.0f), 0.1f);
    EXPECT_FLOAT_EQ(principled::clearcoatAlpha(1.0f), 0.001f);
}

TEST(Principled, ZeroConfigurationIsBurleyDiffuseAtNormalIncidence) {
    // specular = metallic = sheen = clearcoat = subsurface = 0, roughness = 1, wo = n.
    const vec3 base(0.8f, 0.5f, 0.2f);
    auto inst = makeBSDF("disney", {{"base_color", RGBValue{base}},
                                        {"specular", 0.0f},
                                        {"metallic", 0.0f},
                                        {"sheen", 0.0f},
                                        {"clearcoat", 0.0f},
                                        {"subsurface", 0.0f},
                                        {"roughness", 1.0f}});
    const vec3 wo(0, 0, 1);
    const MicrofacetDistribution ggx(MicrofacetType::GGX, 1.0f, 1.0f);
    for (float cosI : {1.0f, 0.8f, 0.5f, 0.2f, 0.05f}) {
        const vec3 wi = test::dirFromCos(cosI, 1.1f);
        const vec3 h = glm::normalize(wo + wi);
        const float cosD = glm::dot(wi, h);
        const float fd90 = 0.5f + 2.0f * cosD * cosD;
        const float burley = (1.0f + (fd90 - 1.0f) * std::pow(1.0f - cosI, 5.0f)) * kInvPi;  // cosθv = 1
        // The specular lobe keeps Schlick's F = F_H towards 1 even with Cspec0 = 0 (Burley's model);
        // at normal view it is tiny. Check the diffuse exactly after removing it, and the whole
        // BRDF against Burley diffuse within 1 %.
        const float fh = std::pow(1.0f - cosD, 5.0f);
        const float spec = fh * ggx.D(h) * ggx.G(wi, wo, h) / (4.0f * cosI * wo.z);
        const SampledSpectrum f = inst.bsdf->eval(wo, wi, kRad);
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(f[c] - spec, base[c] * burley, 1e-5f * base[c] * burley + 1e-7f) << "cosI " << cosI;
            EXPECT_NEAR(f[c], base[c] * burley, 0.01f * base[c] * burley) << "cosI " << cosI;
        }
    }
}

TEST(Principled, MetallicHasNoDiffuseLobe) {
    const vec3 base(0.9f, 0.6f, 0.3f);
    auto metal = makeBSDF("disney", {{"base_color", RGBValue{base}},
                                         {"metallic", 1.0f},
                                         {"roughness", 0.4f},
                                         {"subsurface", 0.7f},
                                         {"sheen", 1.0f},
                                         {"specular", 0.9f}});
    EXPECT_FALSE(metal.bsdf->flags() & kBSDFDiffuse);
    auto dielectric = makeBSDF("disney", {{"metallic", 0.0f}});
    EXPECT_TRUE(dielectric.bsdf->flags() & kBSDFDiffuse);
    // f = (Cd + (1 − Cd) F_H) D G / (4 cosθl cosθv): nothing of the subsurface, sheen or specular.
    const vec2 a = principled::anisotropicAlphas(0.4f, 0.0f);
    const MicrofacetDistribution ggx(MicrofacetType::GGX, a.x, a.y);
    for (float co : {0.9f, 0.4f, 0.1f})
        for (float ci : {0.95f, 0.5f, 0.15f}) {
            const vec3 wo = test::dirFromCos(co, 0.3f), wi = test::dirFromCos(ci, 2.5f);
            const vec3 h = glm::normalize(wo + wi);
            const float fh = std::pow(1.0f - glm::dot(wi, h), 5.0f);
            const float dg = ggx.D(h) * ggx.G(wi, wo, h) / (4.0f * co * ci);
            const SampledSpectrum f = metal.bsdf->eval(wo, wi, kRad);
            for (int c = 0; c < 3; ++c) {
                const float expect = (base[c] + (1.0f - base[c]) * fh) * dg;
                EXPECT_NEAR(f[c], expect, 1e-5f * expect + 1e-8f);
            }
        }
}

TEST(Principled, SpecularTintUsesLuminanceOfRGB) {
    // Normal incidence (wo = wi = n): F_H = 0, G = 1, D = 1/(π α²); the difference between
    // spec_tint 1 and 0 is 0.08 specular (Ctint − 1) D / 4 with Ctint = Cd / lum(rgb(Cd)).
    const vec3 rgb(0.7f, 0.3f, 0.1f);
    const float lum = 0.2126f * rgb.x + 0.7152f * rgb.y + 0.0722f * rgb.z;
    const float r = 0.5f, alpha = r * r;
    const float d = 1.0f / (kPi * alpha * alpha);
    const vec3 n(0, 0, 1);
    for (bool spectral : {false, true}) {
        const SampledWavelengths wl = spectral ? SampledWavelengths::sampleVisible(0.37f, 8)
                                               : SampledWavelengths::rgb(defaultChannelWavelengths());
        auto p1 = test::makeProps("disney", {{"base_color", RGBValue{rgb}}, {"roughness", r}, {"specular", 1.0f},
                                                 {"spec_tint", 1.0f}});
        auto p0 = test::makeProps("disney", {{"base_color", RGBValue{rgb}}, {"roughness", r}, {"specular", 1.0f},
                                                 {"specular_tint", 0.0f}});
        auto t1 = test::makeBSDF(*p1, wl);
        auto t0 = test::makeBSDF(*p0, wl);
        const SampledSpectrum cd = makeRGBSpectrum(rgb, SpectrumKind::Reflectance)->sample(wl);
        const SampledSpectrum diff = t1.bsdf->eval(n, n, kRad) - t0.bsdf->eval(n, n, kRad);
        for (int i = 0; i < wl.size(); ++i) {
            const float expect = 0.08f * (cd[i] / lum - 1.0f) * d / 4.0f;
            EXPECT_NEAR(diff[i], expect, 1e-4f * std::abs(d)) << (spectral ? "spectral " : "rgb ") << i;
        }
    }
}

TEST(Principled, TexturedBaseColourTintInSpectralMode) {
    // base_color from a checkerboard texture; in spectral mode Ctint(λ) = Cd(λ)/lum(rgb(uv)) where
    // rgb(uv) is the texture's RGB value at the shading point (test as above, at two uv cells).
    const vec3 c0(0.7f, 0.3f, 0.1f), c1(0.1f, 0.2f, 0.8f);
    auto makeTex = [&] {
        auto t = std::make_shared<Properties>("texture", "checkerboard", SourceLocation{"<test>", 0});
        t->set("color0", RGBValue{c0}, SourceLocation{});
        t->set("color1", RGBValue{c1}, SourceLocation{});
        return t;
    };
    auto p1 = test::makeProps("disney", {{"roughness", 0.5f}, {"specular", 1.0f}, {"spec_tint", 1.0f}});
    auto p0 = test::makeProps("disney", {{"roughness", 0.5f}, {"specular", 1.0f}, {"spec_tint", 0.0f}});
    p1->set("base_color", makeTex(), SourceLocation{});
    p0->set("base_color", makeTex(), SourceLocation{});
    auto m1 = MaterialRegistry::instance().create(*p1);
    auto m0 = MaterialRegistry::instance().create(*p0);
    auto tex = SpectrumTextureRegistry::instance().create(*makeTex(), SpectrumKind::Reflectance);
    const float d = 1.0f / (kPi * std::pow(0.25f, 2.0f));
    const vec3 n(0, 0, 1);
    Arena arena;
    for (vec2 uv : {vec2(0.25f, 0.25f), vec2(0.75f, 0.25f)}) {
        ShadingPoint sp;
        sp.tex.uv = uv;
        SampledWavelengths wl = SampledWavelengths::sampleVisible(0.61f, 6);
        const SampledSpectrum cd = tex->eval(sp.tex, wl);
        const SampledSpectrum rgb = tex->eval(sp.tex, SampledWavelengths::rgb(defaultChannelWavelengths()));
        const float lum = 0.2126f * rgb[0] + 0.7152f * rgb[1] + 0.0722f * rgb[2];
        const SampledSpectrum diff =
            m1->getBSDF(sp, wl, arena)->eval(n, n, kRad) - m0->getBSDF(sp, wl, arena)->eval(n, n, kRad);
        for (int i = 0; i < wl.size(); ++i)
            EXPECT_NEAR(diff[i], 0.08f * (cd[i] / lum - 1.0f) * d / 4.0f, 1e-4f * d) << "uv " << uv.x << " λ " << i;
    }
}

TEST(PrincipledSampling, SpectralModeConsistency) {
    // Eight wavelengths of an RGB-upsampled base colour: sampling and eval/pdf must stay consistent
    // (the lobe probabilities average over the wavelengths).
    auto p = test::makeProps("disney", {{"base_color", RGBValue{vec3(0.9f, 0.2f, 0.4f)}},
                                            {"roughness", 0.4f},
                                            {"metallic", 0.5f},
                                            {"clearcoat", 0.7f},
                                            {"sheen", 0.5f},
                                            {"anisotropic", 0.4f}});
    auto inst = test::makeBSDF(*p, SampledWavelengths::sampleVisible(0.2f, 8));
    for (float c : {0.9f, 0.3f}) {
        const vec3 wo = test::dirFromCos(c, 1.3f);
        test::Chi2Options opt;
        opt.numTests = 2;
        opt.thetaBins = 40;
        opt.phiBins = 80;
        opt.samples = 1000000;
        const auto chi = test::chi2Test(*inst.bsdf, wo, opt);
        EXPECT_TRUE(chi.passed) << chi.message;
        const auto cons = test::checkConsistency(*inst.bsdf, wo);
        EXPECT_EQ(cons.invalid, 0) << cons.message;
        EXPECT_LT(cons.maxRelErrF, 1e-4f) << cons.message;
        EXPECT_LT(cons.maxRelErrPdf, 1e-4f) << cons.message;
    }
}

TEST(Principled, AnisotropyStretchesAlongTangent) {
    // anisotropic = 0.9: αx > αy, so the lobe is wider when wi leaves the mirror direction along x.
    auto inst = makeBSDF("disney", {{"metallic", 1.0f}, {"roughness", 0.4f}, {"anisotropic", 0.9f}});
    const vec3 wo(0, 0, 1);
    const float off = 0.35f;
    const vec3 wx = glm::normalize(vec3(off, 0, 1)), wy = glm::normalize(vec3(0, off, 1));
    EXPECT_GT(inst.bsdf->eval(wo, wx, kRad)[0], 1.5f * inst.bsdf->eval(wo, wy, kRad)[0]);
}

TEST(Principled, BadParametersThrow) {
    EXPECT_THROW(makeBSDF("disney", {{"metallic", 1.5f}}), Error);
    EXPECT_THROW(makeBSDF("disney", {{"roughness", -0.1f}}), Error);
    EXPECT_THROW(makeBSDF("disney", {{"spec_tint", 0.5f}, {"specular_tint", 0.5f}}), Error);
    EXPECT_THROW(makeBSDF("disney", {{"spec_trans", 0.5f}}), Error);  // not supported: unknown
}

struct PrincipledCase {
    float roughness, anisotropic, metallic, clearcoat, clearcoatGloss, sheen, subsurface;
};

std::vector<PrincipledCase> principledCases() {
    return {
        {0.3f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f},  // glossy dielectric
        {0.6f, 0.0f, 0.0f, 0.0f, 0.0f, 0.5f, 0.5f},  // + sheen, subsurface
        {1.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f, 0.0f},  // rough
        {0.3f, 0.0f, 1.0f, 0.0f, 0.0f, 0.0f, 0.0f},  // metal
        {0.5f, 0.8f, 1.0f, 0.0f, 0.0f, 0.0f, 0.0f},  // anisotropic metal
        {0.4f, 1.0f, 0.5f, 0.0f, 0.0f, 0.0f, 0.0f},  // anisotropic, half metal
        {0.5f, 0.0f, 0.0f, 1.0f, 0.0f, 0.0f, 0.0f},  // clear coat α = 0.1
        {0.7f, 0.5f, 0.3f, 1.0f, 0.5f, 0.3f, 0.2f},  // everything, clear coat α = 0.0505
    };
}

test::BSDFInstance makeCase(const PrincipledCase& k) {
    return makeBSDF("disney", {{"base_color", RGBValue{vec3(0.8f, 0.45f, 0.2f)}},
                                   {"roughness", k.roughness},
                                   {"anisotropic", k.anisotropic},
                                   {"metallic", k.metallic},
                                   {"clearcoat", k.clearcoat},
                                   {"clearcoat_gloss", k.clearcoatGloss},
                                   {"sheen", k.sheen},
                                   {"subsurface", k.subsurface},
                                   {"spec_tint", 0.3f},
                                   {"sheen_tint", 0.5f}});
}

TEST(PrincipledSampling, ChiSquareConsistencyAndPdf) {
    const auto cases = principledCases();
    const float coss[] = {0.95f, 0.5f, 0.1f, 0.03f};
    const int numTests = int(cases.size() * std::size(coss));
    for (const auto& k : cases) {
        auto inst = makeCase(k);
        for (float c : coss) {
            const vec3 wo = test::dirFromCos(c, 0.4f);
            test::Chi2Options opt;
            opt.numTests = numTests;
            opt.thetaBins = 40;
            opt.phiBins = 80;
            opt.samples = 1000000;
            const auto chi = test::chi2Test(*inst.bsdf, wo, opt);
            EXPECT_TRUE(chi.passed) << "r " << k.roughness << " aniso " << k.anisotropic << " metal " << k.metallic
                                    << " cc " << k.clearcoat << "/" << k.clearcoatGloss << " cos " << c << ": "
                                    << chi.message;
            const auto cons = test::checkConsistency(*inst.bsdf, wo);
            EXPECT_EQ(cons.invalid, 0) << cons.message;
            EXPECT_LT(cons.maxRelErrF, 1e-4f) << cons.message;
            EXPECT_LT(cons.maxRelErrPdf, 1e-4f) << cons.message;
            const auto pi = test::pdfIntegral(*inst.bsdf, wo);
            EXPECT_LE(pi.mean, 1.0 + 5 * pi.stderr_ + 1e-3);
        }
    }
}

TEST(PrincipledSampling, Reciprocity) {
    for (const auto& k : principledCases()) {
        auto inst = makeCase(k);
        EXPECT_LT(test::reciprocityError(*inst.bsdf), 1e-3f) << "r " << k.roughness << " aniso " << k.anisotropic;
    }
}

TEST(PrincipledFurnace, MetalIsEnergyConserving) {
    // metallic = 1, base colour 1: F = 1, single-scattering GGX loses energy but never gains.
    for (float r : {0.1f, 0.3f, 0.6f, 1.0f})
        for (float aniso : {0.0f, 0.9f}) {
            auto inst = makeBSDF("disney",
                                 {{"base_color", 1.0f}, {"metallic", 1.0f}, {"roughness", r}, {"anisotropic", aniso}});
            for (float c : {1.0f, 0.6f, 0.2f, 0.05f}) {
                const auto a = test::albedo(*inst.bsdf, test::dirFromCos(c, 0.2f), 200000)[0];
                EXPECT_LE(a.mean, 1.0 + 4 * a.stderr_) << "r " << r << " aniso " << aniso << " cos " << c;
                EXPECT_GT(a.mean, 0.1) << "r " << r << " aniso " << aniso << " cos " << c;
            }
        }
}

// Directional albedos (red channel, base colour 1 unless noted; the table of
// docs/materials_principled_cloth.md is printed by `material_albedo --table principled`): every
// configuration stays within [0.2, 1.6] at every angle — the Disney model is not energy
// conserving (the diffuse and sheen terms are added to the specular lobe without scaling), and
// 1.6 bounds that gain; the metallic rows, a single GGX lobe, stay ≤ 1 (to 4 standard errors).
TEST(PrincipledFurnace, AlbedosWithinTheirBounds) {
    const float coss[] = {1.0f, 0.7f, 0.4f, 0.2f, 0.05f};
    auto check = [&](const char* name, std::initializer_list<test::Param> params, double hi) {
        auto inst = makeBSDF("disney", params);
        for (float c : coss) {
            const auto a = test::albedo(*inst.bsdf, test::dirFromCos(c, 0.2f), 200000)[0];
            EXPECT_GE(a.mean, 0.2) << name << " cos " << c;
            EXPECT_LE(a.mean, hi + 4 * a.stderr_) << name << " cos " << c;
        }
    };
    for (float r : {0.1f, 0.3f, 0.6f, 1.0f}) check("metallic", {{"base_color", 1.0f}, {"metallic", 1.0f}, {"roughness", r}}, 1.0);
    check("metallic, anisotropic 0.9", {{"base_color", 1.0f}, {"metallic", 1.0f}, {"roughness", 0.6f}, {"anisotropic", 0.9f}}, 1.0);
    check("dielectric defaults", {{"base_color", 1.0f}}, 1.6);
    check("dielectric, roughness 1", {{"base_color", 1.0f}, {"roughness", 1.0f}}, 1.6);
    check("dielectric, roughness 0.2", {{"base_color", 1.0f}, {"roughness", 0.2f}}, 1.6);
    check("specular 0, roughness 1", {{"base_color", 1.0f}, {"specular", 0.0f}, {"roughness", 1.0f}}, 1.6);
    check("specular 0, roughness 0", {{"base_color", 1.0f}, {"specular", 0.0f}, {"roughness", 0.0f}}, 1.6);
    check("subsurface 1", {{"base_color", 1.0f}, {"subsurface", 1.0f}}, 1.6);
    check("sheen 1", {{"base_color", 1.0f}, {"sheen", 1.0f}}, 1.6);
    check("clearcoat 1, gloss 1", {{"base_color", 1.0f}, {"clearcoat", 1.0f}, {"clearcoat_gloss", 1.0f}}, 1.6);
    check("everything 1", {{"base_color", 1.0f}, {"specular", 1.0f}, {"sheen", 1.0f}, {"clearcoat", 1.0f}, {"subsurface", 1.0f}}, 1.6);
}

}  // namespace
}  // namespace iris
