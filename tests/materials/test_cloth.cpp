// Tests of the `cloth` (Charlie sheen + wrapped diffuse) and `velvet` (Ashikhmin) materials:
// distribution normalisation, the Λ fit against numerical Smith Λ, analytic albedos of the
// wrapped diffuse, chi-square sampling tests, eval/pdf consistency, reciprocity, and the
// bounds of the measured albedo table of docs/materials_principled_cloth.md (material_albedo --table cloth).
#include <cstdio>

#include <gtest/gtest.h>

#include "core/error.h"
#include "materials/cloth_distributions.h"
#include "tests/support/bsdf_test_util.h"

namespace iris {
namespace {

using test::makeBSDF;

/// ∫ D(θh) cosθh dω over the hemisphere, by the midpoint rule in θ (D is isotropic).
template <typename F>
double hemisphereIntegralCos(F&& d, int n = 200000) {
    double sum = 0;
    const double dt = 0.5 * M_PI / n;
    for (int i = 0; i < n; ++i) {
        const double t = (i + 0.5) * dt;
        sum += d(float(std::cos(t))) * std::cos(t) * std::sin(t);
    }
    return 2.0 * M_PI * sum * dt;
}

TEST(ClothDistribution, CharlieIsNormalised) {
    for (float alpha : {0.05f, 0.15f, 0.3f, 0.5f, 0.8f, 1.0f}) {
        const double integral = hemisphereIntegralCos([&](float c) { return cloth::charlieD(alpha, c); });
        EXPECT_NEAR(integral, 1.0, 1e-3) << "alpha " << alpha;
    }
}

TEST(ClothDistribution, VelvetIsNormalised) {
    for (float sigma : {0.1f, 0.25f, 0.5f, 1.0f, 2.0f}) {
        const double integral = hemisphereIntegralCos([&](float c) { return cloth::velvetD(sigma, c); });
        EXPECT_NEAR(integral, 1.0, 1e-3) << "sigma " << sigma;
    }
}

/// Smith Λ of an isotropic distribution by numerical integration of the projected area of visible
/// microfacets: 1 + Λ(ω) = ∫ D(m) max(0, ω·m) dm / cosθ  (Heitz 2014, eqs. 17 and 71 rearranged).
double numericalLambda(float cosTheta, const std::function<float(float)>& d) {
    const double sinT = std::sqrt(1.0 - double(cosTheta) * cosTheta);
    const int nt = 2000, np = 400;
    double sum = 0;
    for (int i = 0; i < nt; ++i) {
        const double t = (i + 0.5) * 0.5 * M_PI / nt;
        const double ct = std::cos(t), st = std::sin(t);
        double inner = 0;
        for (int j = 0; j < np; ++j) {
            const double ph = (j + 0.5) * 2 * M_PI / np;
            inner += std::max(0.0, sinT * st * std::cos(ph) + cosTheta * ct);
        }
        sum += d(float(ct)) * inner * st;
    }
    sum *= (0.5 * M_PI / nt) * (2 * M_PI / np);
    return sum / cosTheta - 1.0;
}

TEST(ClothDistribution, CharlieLambdaFitMatchesNumericalSmith) {
    // The published fit is an approximation: its masking term G1 = 1/(1+Λ) agrees with the
    // numerically integrated one to 0.040 at α = 0.2 (worst measured), 0.02 at α = 0.5 and 0.008
    // at α = 1. Tolerances: 0.05 overall, 0.015 at α = 1 (interpolating the table the wrong way
    // round, t = r² instead of (1 − r)², is off by 0.3 there).
    float worst = 0;
    for (float alpha : {0.2f, 0.5f, 1.0f}) {
        for (float c : {0.1f, 0.3f, 0.5f, 0.7f, 0.9f}) {
            const double ln = numericalLambda(c, [&](float x) { return cloth::charlieD(alpha, x); });
            const float g1Fit = 1.0f / (1.0f + cloth::charlieLambda(c, alpha));
            const float g1Num = float(1.0 / (1.0 + ln));
            worst = std::max(worst, std::abs(g1Fit - g1Num));
            EXPECT_NEAR(g1Fit, g1Num, alpha == 1.0f ? 0.015f : 0.05f) << "alpha " << alpha << " cos " << c;
        }
    }
    std::printf("Charlie G1: max |fit − numerical| = %.4f\n", worst);
}

TEST(ClothDistribution, CharlieShadowingIsBounded) {
    for (float alpha : {0.1f, 0.5f, 1.0f})
        for (float co : {0.05f, 0.5f, 1.0f})
            for (float ci : {0.05f, 0.5f, 1.0f}) {
                const float g = cloth::charlieG(co, ci, alpha);
                EXPECT_GT(g, 0.0f);
                EXPECT_LE(g, 1.0f);
            }
}

TEST(Cloth, LambertWithoutSheenOrWrap) {
    auto inst = makeBSDF("cloth", {{"base_color", RGBValue{vec3(0.2f, 0.5f, 0.8f)}}, {"sheen_color", 0.0f}});
    const vec3 wo = test::dirFromCos(0.6f), wi = test::dirFromCos(0.3f, 2.0f);
    const SampledSpectrum f = inst.bsdf->eval(wo, wi, TransportMode::Radiance);
    EXPECT_FLOAT_EQ(f[0], 0.2f * kInvPi);
    EXPECT_FLOAT_EQ(f[1], 0.5f * kInvPi);
    EXPECT_FLOAT_EQ(f[2], 0.8f * kInvPi);
    // One-sided.
    EXPECT_TRUE(inst.bsdf->eval(vec3(wo.x, wo.y, -wo.z), wi, TransportMode::Radiance).isBlack());
    EXPECT_FALSE(inst.bsdf->sample(vec3(wo.x, wo.y, -wo.z), 0.3f, vec2(0.4f, 0.6f), TransportMode::Radiance));
}

TEST(Cloth, WrappedDiffuseAlbedoMatchesAnalytic) {
    // Directional albedo of ρ/π (cosθi + w)/(1 + w)² · s(cosθi): with no subsurface colour (s = 1)
    // it is (1 + 2w)/(1 + w)²; with subsurface colour 0, s = cosθi and it is (2/3 + w)/(1 + w)².
    for (float w : {0.0f, 0.5f, 1.0f}) {
        auto plain = makeBSDF("cloth", {{"base_color", 1.0f}, {"sheen_color", 0.0f}, {"wrap", w}});
        auto ss0 = makeBSDF("cloth",
                            {{"base_color", 1.0f}, {"sheen_color", 0.0f}, {"wrap", w}, {"subsurface_color", 0.0f}});
        const vec3 wo = test::dirFromCos(0.7f);
        const auto a = test::albedo(*plain.bsdf, wo)[0];
        const auto b = test::albedo(*ss0.bsdf, wo)[0];
        EXPECT_NEAR(a.mean, (1 + 2 * w) / sqr(1 + w), 4 * a.stderr_ + 1e-4) << "w " << w;
        EXPECT_NEAR(b.mean, (2.0 / 3.0 + w) / sqr(1 + w), 4 * b.stderr_ + 1e-4) << "w " << w;
        EXPECT_LE(a.mean, 1.0 + 4 * a.stderr_);
    }
}

struct SamplingCase {
    const char* type;
    float rough;  // roughness (cloth) or sigma (velvet)
    const char* vis;
    float wrap;
    bool subsurface;
    float cosO;
};

std::vector<SamplingCase> samplingCases() {
    std::vector<SamplingCase> cases;
    for (float r : {0.1f, 0.4f, 1.0f})
        for (const char* vis : {"charlie", "neubelt"})
            for (float c : {0.95f, 0.5f, 0.08f}) cases.push_back({"cloth", r, vis, 0.0f, false, c});
    for (float c : {0.9f, 0.1f}) cases.push_back({"cloth", 0.3f, "charlie", 0.5f, true, c});
    for (float s : {0.1f, 0.5f, 1.0f})
        for (float c : {0.9f, 0.3f, 0.05f}) cases.push_back({"velvet", s, "", 0, false, c});
    return cases;
}

test::BSDFInstance makeCase(const SamplingCase& k) {
    if (std::string(k.type) == "velvet")
        return makeBSDF("velvet", {{"reflectance", RGBValue{vec3(0.9f, 0.6f, 0.3f)}}, {"sigma", k.rough}});
    auto props = test::makeProps("cloth", {{"base_color", RGBValue{vec3(0.6f, 0.3f, 0.2f)}},
                                           {"sheen_color", RGBValue{vec3(0.9f, 0.8f, 0.7f)}},
                                           {"roughness", k.rough},
                                           {"visibility", std::string(k.vis)},
                                           {"wrap", k.wrap}});
    if (k.subsurface) props->set("subsurface_color", RGBValue{vec3(0.8f, 0.2f, 0.1f)}, SourceLocation{});
    return test::makeBSDF(*props, SampledWavelengths::rgb(defaultChannelWavelengths()));
}

TEST(ClothSampling, ChiSquareConsistencyAndPdf) {
    // Both materials sample p ∝ cos^(1/2)θ whatever their parameters and wo, so the chi-square
    // test runs once per material (two wo); eval/pdf consistency and ∫pdf = 1 run for every case.
    const auto cases = samplingCases();
    const int chi2Tests = 4;
    int chi2Run = 0;
    for (size_t i = 0; i < cases.size(); ++i) {
        const auto& k = cases[i];
        auto inst = makeCase(k);
        const vec3 wo = test::dirFromCos(k.cosO, 0.7f);
        const bool firstOfType = i == 0 || std::string(cases[i - 1].type) != k.type;
        const bool lastOfType = i + 1 == cases.size() || std::string(cases[i + 1].type) != k.type;
        if (firstOfType || lastOfType) {
            test::Chi2Options opt;
            opt.numTests = chi2Tests;
            const auto chi = test::chi2Test(*inst.bsdf, wo, opt);
            EXPECT_TRUE(chi.passed) << k.type << " r " << k.rough << " " << k.vis << " cos " << k.cosO << ": "
                                    << chi.message;
            ++chi2Run;
        }
        const auto cons = test::checkConsistency(*inst.bsdf, wo);
        EXPECT_EQ(cons.invalid, 0) << cons.message;
        EXPECT_LT(cons.maxRelErrF, 1e-4f) << cons.message;
        EXPECT_LT(cons.maxRelErrPdf, 1e-4f) << cons.message;
        const auto pi = test::pdfIntegral(*inst.bsdf, wo);
        EXPECT_NEAR(pi.mean, 1.0, 5 * pi.stderr_ + 1e-3);
    }
    EXPECT_EQ(chi2Run, chi2Tests);
}

TEST(ClothSampling, Reciprocity) {
    for (const char* vis : {"charlie", "neubelt"})
        for (float r : {0.2f, 0.7f}) {
            auto inst = makeBSDF("cloth", {{"roughness", r}, {"visibility", std::string(vis)}});
            EXPECT_LT(test::reciprocityError(*inst.bsdf), 1e-4f) << vis << " " << r;
        }
    for (float s : {0.2f, 0.7f}) {
        auto inst = makeBSDF("velvet", {{"sigma", s}});
        EXPECT_LT(test::reciprocityError(*inst.bsdf), 1e-4f) << "velvet " << s;
    }
    // The wrapped diffuse depends on wi only: not reciprocal by design (documented).
    auto wrapped = makeBSDF("cloth", {{"wrap", 0.5f}, {"sheen_color", 0.0f}});
    EXPECT_GT(test::reciprocityError(*wrapped.bsdf), 1e-2f);
}

TEST(Cloth, BadParametersThrow) {
    EXPECT_THROW(makeBSDF("cloth", {{"visibility", std::string("ggx")}}), Error);
    EXPECT_THROW(makeBSDF("cloth", {{"roughness", 0.0f}}), Error);
    EXPECT_THROW(makeBSDF("cloth", {{"wrap", -0.5f}}), Error);
    EXPECT_THROW(makeBSDF("cloth", {{"colour", 0.5f}}), Error);
    EXPECT_THROW(makeBSDF("velvet", {{"sigma", 0.0f}}), Error);
}

// Measured directional albedos (white furnace, sample() weights) for the docs. Sheen-only
// lobes (base colour 0, sheen colour 1) and velvet with reflectance 1. Asserts only what the
// models guarantee: finite, non-negative; prints the table (copied into the docs).
// The cloth lobes' directional albedos (the table of docs/materials_principled_cloth.md is
// printed by `material_albedo --table cloth`): each sheen lobe alone and velvet stay within
// [0, 1] (to 4 standard errors); cloth adds its sheen to the diffuse without scaling, so base 1 +
// sheen 1 exceeds 1 and grows towards grazing, but stays below the sum of two unit lobes.
TEST(ClothAlbedo, SheenLobesConserveEnergyAndTheLayeredSumGains) {
    const float coss[] = {1.0f, 0.7f, 0.4f, 0.2f, 0.05f};
    auto albedos = [&](const test::BSDFInstance& inst) {
        std::vector<test::Estimate> out;
        for (float c : coss) out.push_back(test::albedo(*inst.bsdf, test::dirFromCos(c), 200000)[0]);
        return out;
    };
    for (const char* vis : {"charlie", "neubelt"})
        for (float r : {0.1f, 0.3f, 0.6f, 1.0f})
            for (const auto& a : albedos(makeBSDF("cloth", {{"base_color", 0.0f}, {"sheen_color", 1.0f}, {"roughness", r},
                                                           {"visibility", std::string(vis)}}))) {
                EXPECT_GE(a.mean, 0.0) << vis << " α " << r;
                EXPECT_LE(a.mean, 1.0 + 4 * a.stderr_) << vis << " α " << r;
            }
    for (float s : {0.1f, 0.3f, 0.6f, 1.0f})
        for (const auto& a : albedos(makeBSDF("velvet", {{"reflectance", 1.0f}, {"sigma", s}}))) {
            EXPECT_GT(a.mean, 0.05) << "velvet σ " << s;
            EXPECT_LE(a.mean, 1.0 + 4 * a.stderr_) << "velvet σ " << s;
        }
    const auto both = albedos(makeBSDF("cloth", {{"base_color", 1.0f}, {"sheen_color", 1.0f}, {"roughness", 0.3f}}));
    for (size_t i = 0; i < both.size(); ++i) {
        EXPECT_GT(both[i].mean, 1.0) << "cos " << coss[i];
        EXPECT_LT(both[i].mean, 2.0) << "cos " << coss[i];
        if (i > 0) EXPECT_GT(both[i].mean, both[i - 1].mean) << "the gain grows towards grazing";
    }
}

}  // namespace
}  // namespace iris
