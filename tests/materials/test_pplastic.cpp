// pplastic (Mitsuba 3's polarized plastic, Baek et al. 2018; materials/pplastic.cpp): sampling
// (χ², consistency), energy (albedo ≤ 1), the unpolarized value the model defines, the polarization
// of each lobe (Brewster's angle leaves the specular lobe without p light; the diffuse lobe's light
// is p-polarized by the Fresnel transmittances), and located errors for bad parameters. Its generic
// Mueller properties (M00 = eval, physical, reciprocal) are in test_bsdf_mueller.cpp's list.
#include <gtest/gtest.h>

#include <cmath>

#include "render/loader/scene_loader.h"
#include "spectral/stokes_basis.h"
#include "tests/support/bsdf_test_util.h"
#include "tests/support/error_of.h"

using namespace iris;
using namespace iris::test;

namespace {

constexpr TransportMode kRad = TransportMode::Radiance;
SampledWavelengths spectralWl() { return SampledWavelengths::sampleVisible(0.37f, 4); }

/// Unpolarized Fresnel reflectance from Born & Wolf §1.5.2's amplitudes (independent of materials/).
double fresnelR(double ci, double n) {
    const double ct = std::sqrt(1.0 - (1.0 - ci * ci) / (n * n));
    const double rs = (ci - n * ct) / (ci + n * ct), rp = (n * ci - ct) / (n * ci + ct);
    return 0.5 * (rs * rs + rp * rp);
}

/// Degree of linear polarization along s of unpolarized light transmitted at cos θi:
/// (T_s − T_p)/(T_s + T_p), T = 1 − r² (Born & Wolf §1.5.2).
double transmittedSOverS0(double ci, double n) {
    const double ct = std::sqrt(1.0 - (1.0 - ci * ci) / (n * n));
    const double rs = (ci - n * ct) / (ci + n * ct), rp = (n * ci - ct) / (n * ci + ct);
    const double ts = 1.0 - rs * rs, tp = 1.0 - rp * rp;
    return (ts - tp) / (ts + tp);
}

/// The Stokes vector (S0, S1 in the s-axis basis normalize(axis × wo)) of unpolarized light after M.
std::pair<float, float> unpolarizedOutputInSBasis(const MuellerSpectrum& Min, const vec3& axis, const vec3& wo, int lane) {
    const MuellerSpectrum M = Min.expanded();
    const vec3 s = glm::normalize(glm::cross(axis, wo));
    const auto R = stokesBasisRotation(wo, stokesBasis(wo), s);
    return {M(0, 0)[lane], R.c2 * M(1, 0)[lane] + R.s2 * M(2, 0)[lane]};  // rotator · S (first two rows)
}

std::string loadError(const std::string& bsdf) {
    return errorOf([&] { loadSceneFromString("<scene version=\"3.0.0\">\n<shape type=\"sphere\">\n" + bsdf + "</shape></scene>", "."); });
}

}  // namespace

TEST(PPlastic, SamplingMatchesPdfChi2AndEval) {
    struct Case {
        const char* dist;
        float alpha, cosO;
        bool visible;
    };
    const Case cases[] = {{"beckmann", 0.1f, 0.8f, true}, {"ggx", 0.3f, 0.4f, true}, {"ggx", 0.05f, 0.95f, true},
                          {"beckmann", 0.6f, 0.15f, true}, {"ggx", 0.2f, 0.5f, false}};
    Chi2Options opt;
    opt.numTests = 5;
    for (const Case& k : cases) {
        auto inst = makeBSDF("pplastic", {{"distribution", std::string(k.dist)}, {"alpha", k.alpha}, {"sample_visible", k.visible},
                                          {"diffuse_reflectance", RGBValue{vec3(0.8f, 0.3f, 0.05f)}}});
        const vec3 wo = dirFromCos(k.cosO, 0.4f);
        const Chi2Result r = chi2Test(*inst.bsdf, wo, opt);
        EXPECT_TRUE(r.passed) << k.dist << " alpha " << k.alpha << ": " << r.message;
        const ConsistencyResult c = checkConsistency(*inst.bsdf, wo);
        EXPECT_EQ(c.invalid, 0) << c.message;
        EXPECT_LT(c.maxRelErrF, 1e-5f);
        EXPECT_LT(c.maxRelErrPdf, 1e-5f);
        const Estimate pdfMass = pdfIntegral(*inst.bsdf, wo);
        EXPECT_LE(pdfMass.mean, 1.0 + 5 * pdfMass.stderr_) << k.dist << " alpha " << k.alpha;
    }
}

TEST(PPlastic, AlbedoAtMostOne) {
    // Mitsuba's doc: the sum "does not result in any extra energy" but is "not energy conserving".
    for (const char* dist : {"beckmann", "ggx"})
        for (float alpha : {0.01f, 0.3f, 1.0f})
            for (float eta : {1.5f, 3.0f, 0.7f}) {
                auto inst = makeBSDF("pplastic", {{"distribution", std::string(dist)}, {"alpha", alpha}, {"eta", eta},
                                                  {"diffuse_reflectance", 1.0f}});
                for (float c : {0.05f, 0.5f, 1.0f}) {
                    const auto a = albedo(*inst.bsdf, dirFromCos(c), 60000);
                    EXPECT_LE(a[0].mean, 1.0 + 5 * a[0].stderr_) << dist << " alpha " << alpha << " eta " << eta << " cos " << c;
                    EXPECT_GT(a[0].mean, 0.02) << dist << " alpha " << alpha << " eta " << eta << " cos " << c;
                }
            }
}

TEST(PPlastic, UnpolarizedValueIsMitsubasSum) {
    // ks = 0: ρ (1 − F(μi)) (1 − F(μo)) / π, no 1/η² and no internal reflections (Mitsuba 3 pplastic).
    const float eta = 1.6f;
    auto diffuseOnly = makeBSDF("pplastic", {{"eta", eta}, {"specular_reflectance", 0.0f}, {"diffuse_reflectance", 0.7f}});
    for (float ci : {0.2f, 0.6f, 1.0f})
        for (float co : {0.1f, 0.5f, 0.9f}) {
            const vec3 wo = dirFromCos(co, 0.3f), wi = dirFromCos(ci, 2.1f);
            const double expect = 0.7 * (1 - fresnelR(ci, eta)) * (1 - fresnelR(co, eta)) / M_PI;
            EXPECT_NEAR(diffuseOnly.bsdf->eval(wo, wi, kRad)[0], expect, 1e-5 * expect);
        }
    // The defaults are Mitsuba 3's: η = 1.49 / 1.000277, ρ = 0.5.
    auto def = makeBSDF("pplastic", {{"specular_reflectance", 0.0f}});
    const double e = 1.49 / 1.000277;
    EXPECT_NEAR(def.bsdf->eval(dirFromCos(0.5f), dirFromCos(0.7f, 1.0f), kRad)[1],
                0.5 * (1 - fresnelR(0.5, e)) * (1 - fresnelR(0.7, e)) / M_PI, 1e-6);
}

TEST(PPlastic, SpecularLobeAtBrewstersAngleHasNoPPart) {
    // A microfacet h seen at Brewster's angle, wo · h = cos θ_B, tan θ_B = η: r_p = 0 (Born & Wolf
    // §1.5.3), so unpolarized light leaves fully polarized along the s axis h × wo.
    const float eta = 1.5f, thetaB = std::atan(eta);
    auto spec = makeBSDF("pplastic", {{"eta", eta}, {"alpha", 0.2f}, {"diffuse_reflectance", 0.0f}}, spectralWl());
    for (float tilt : {0.0f, 0.15f, 0.3f}) {
        const vec3 h = glm::normalize(vec3(std::sin(tilt), 0.1f * tilt, std::cos(tilt)));
        const Frame f = Frame::fromNormal(h);
        const vec3 wo = f.toWorld(vec3(std::sin(thetaB) * std::cos(0.6f), std::sin(thetaB) * std::sin(0.6f), std::cos(thetaB)));
        const vec3 wi = reflect(wo, h);
        ASSERT_GT(wi.z, 0.0f);
        ASSERT_GT(wo.z, 0.0f);
        const MuellerSpectrum M = spec.bsdf->evalMueller(wo, wi, kRad);
        for (int l = 0; l < 4; ++l) {
            const auto [s0, s1] = unpolarizedOutputInSBasis(M, h, wo, l);
            EXPECT_GT(s0, 0.0f);
            EXPECT_NEAR(s1 / s0, 1.0f, 1e-4f) << "tilt " << tilt;
        }
    }
    // Away from Brewster's angle the p part is there: S1/S0 < 1 (the test can fail).
    const vec3 wo = dirFromCos(0.9f, 0.2f), wi = reflect(wo, vec3(0, 0, 1));
    const auto [s0, s1] = unpolarizedOutputInSBasis(spec.bsdf->evalMueller(wo, wi, kRad), vec3(0, 0, 1), wo, 0);
    EXPECT_LT(s1 / s0, 0.5f);
}

TEST(PPlastic, DiffuseLobeIsPPolarizedByTheFresnelTransmittances) {
    // ks = 0: unpolarized light leaves with S1/S0 = (T_s − T_p)/(T_s + T_p) at θo in the s basis
    // n × wo (negative: p-polarized), whatever wi; an input polarized along s at wi is transmitted
    // less than along p by the first refraction.
    const float eta = 1.5f;
    auto diff = makeBSDF("pplastic", {{"eta", eta}, {"specular_reflectance", 0.0f}, {"diffuse_reflectance", 0.6f}}, spectralWl());
    for (float co : {0.9f, 0.5f, 0.1f})
        for (float ci : {1.0f, 0.7f, 0.2f}) {
            const vec3 wo = dirFromCos(co, 0.4f), wi = dirFromCos(ci, 2.5f);
            const MuellerSpectrum M = diff.bsdf->evalMueller(wo, wi, kRad);
            const auto [s0, s1] = unpolarizedOutputInSBasis(M, vec3(0, 0, 1), wo, 2);
            EXPECT_NEAR(s1 / s0, transmittedSOverS0(co, eta), 2e-5) << "cos o " << co << " cos i " << ci;
            EXPECT_LE(s1, 0.0f);
        }
    const vec3 wo = dirFromCos(0.6f, 0.4f), wi = dirFromCos(0.15f, 2.5f);
    const MuellerSpectrum M = diff.bsdf->evalMueller(wo, wi, kRad).expanded();
    // Light along the s axis n × (−wi) of the incoming beam: Stokes (1, 1, 0, 0) in that basis.
    const vec3 sIn = glm::normalize(glm::cross(vec3(0, 0, 1), -wi));
    const auto R = stokesBasisRotation(-wi, sIn, stokesBasis(-wi));
    const float sPol = M(0, 0)[0] + M(0, 1)[0] * R.c2 - M(0, 2)[0] * R.s2;  // row 0 · rotator(θ) (1, 1, 0, 0)
    const float pPol = M(0, 0)[0] - M(0, 1)[0] * R.c2 + M(0, 2)[0] * R.s2;
    EXPECT_NEAR(sPol / pPol, (1 + transmittedSOverS0(0.15, eta)) / (1 - transmittedSOverS0(0.15, eta)), 1e-4);
    EXPECT_LT(sPol, 0.8f * pPol);
}

TEST(PPlastic, WrongParametersAreRejectedWithTheirLine) {
    const auto has = contains;
    std::string e = loadError("<bsdf type=\"pplastic\">\n<float name=\"alpha\" value=\"-0.1\"/>\n</bsdf>\n");
    EXPECT_TRUE(has(e, "<string>:4:") && has(e, "alpha must be >= 0")) << e;
    e = loadError("<bsdf type=\"pplastic\">\n<float name=\"eta\" value=\"0\"/>\n</bsdf>\n");
    EXPECT_TRUE(has(e, "<string>:4:") && has(e, "eta must be > 0")) << e;
    e = loadError("<bsdf type=\"pplastic\">\n<float name=\"eta\" value=\"-1.5\"/>\n</bsdf>\n");
    EXPECT_TRUE(has(e, "<string>:4:") && has(e, "eta must be > 0")) << e;
    e = loadError("<bsdf type=\"pplastic\">\n<float name=\"int_ior\" value=\"1.3\"/>\n<float name=\"ext_ior\" value=\"1.3\"/>\n</bsdf>\n");
    EXPECT_TRUE(has(e, "<string>:4:") && has(e, "must differ")) << e;
    e = loadError("<bsdf type=\"pplastic\">\n<float name=\"eta\" value=\"1.5\"/>\n<float name=\"int_ior\" value=\"1.3\"/>\n</bsdf>\n");
    EXPECT_TRUE(has(e, "not both")) << e;
    EXPECT_EQ(loadError("<bsdf type=\"pplastic\">\n<float name=\"alpha\" value=\"0\"/>\n</bsdf>\n"), "");  // Mitsuba: clamped to 1e-4
}

TEST(PPlastic, MeasuredPolarizedIsRefusedWithWhatIsMissing) {
    // docs/polarization.md: no .pbsdf file to test a reader against, so the plugin is not implemented.
    const std::string e = loadError("<bsdf type=\"measured_polarized\">\n<float name=\"alpha_sample\" value=\"0.02\"/>\n</bsdf>\n");
    EXPECT_TRUE(contains(e, "<string>:3:") && contains(e, "measured_polarized") && contains(e, "pplastic")) << e;
}
