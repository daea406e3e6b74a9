// Phase functions (media/phase/): χ² goodness of fit of sample() against pdf() with the BSDF
// harness (tests/support/bsdf_test_util.h; a phase function is wrapped as a BSDF whose local frame
// is the world frame), normalisation ∫p dω = 1, sample() consistent with eval()/pdf(), symmetry,
// Henyey–Greenstein's mean cosine equal to g and its forward direction, Rayleigh's closed form,
// and located errors for bad parameters.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "media/phase/phase_function.h"
#include "tests/support/bsdf_test_util.h"
#include "tests/support/phase_test_util.h"

using namespace iris;
using namespace iris::test;

namespace {

struct Case {
    const char* type;
    float g;  // for hg
};

std::shared_ptr<PhaseFunction> make(const Case& c) {
    return std::string(c.type) == "hg" ? makePhase("hg", {{"g", c.g}}) : makePhase(c.type);
}

const Case kCases[] = {{"isotropic", 0}, {"rayleigh", 0}, {"hg", 0.0f}, {"hg", 0.3f}, {"hg", -0.5f}, {"hg", 0.9f}};

}  // namespace

TEST(PhaseFunctions, ChiSquareAgainstTheirPdf) {
    Chi2Options opt;
    opt.numTests = 3 * int(std::size(kCases));
    for (const Case& c : kCases) {
        const auto p = make(c);
        const PhaseAsBSDF b(*p);
        for (const vec3& wo : {vec3(0, 0, 1), glm::normalize(vec3(0.3f, -0.5f, 0.8f)), glm::normalize(vec3(1, 0.2f, -0.1f))}) {
            const auto r = chi2Test(b, wo, opt);
            EXPECT_TRUE(r.passed) << c.type << " g=" << c.g << ": " << r.message;
            EXPECT_NEAR(r.pdfMass, 1.0, 2e-3) << c.type << " g=" << c.g;
        }
    }
}

TEST(PhaseFunctions, ChiSquareRejectsAMismatchedPdf) {
    // Samples of hg(0.5) tested against the pdf of hg(0.3): the harness must reject them.
    const auto sampler = makePhase("hg", {{"g", 0.5f}}), wrong = makePhase("hg", {{"g", 0.3f}});
    EXPECT_FALSE(chi2Test(PhaseAsBSDF(*wrong, vec3(0.0f), sampler.get()), vec3(0, 0, 1)).passed);
}

TEST(PhaseFunctions, NormalisedSymmetricAndConsistentWithTheirSamples) {
    const vec3 wo = glm::normalize(vec3(0.2f, 0.4f, -0.9f));
    for (const Case& c : kCases) {
        const auto p = make(c);
        const auto [integral, stdError, meanCos] = integratePhase(*p, vec3(0.0f), wo);
        EXPECT_NEAR(integral, 1.0, c.g > 0.8f ? 0.05 : 0.01) << c.type << " g=" << c.g;
        Pcg32 rng(1, 2);
        for (int i = 0; i < 2000; ++i) {
            const auto s = p->sample(vec3(0.0f), wo, vec2(rng.uniform(), rng.uniform()));
            ASSERT_TRUE(s);
            EXPECT_NEAR(glm::length(s->wi), 1.0f, 1e-4f);
            EXPECT_NEAR(s->p, p->eval(vec3(0.0f), wo, s->wi), 1e-4f * s->p);
            EXPECT_NEAR(s->pdf, p->pdf(vec3(0.0f), wo, s->wi), 1e-4f * s->pdf);
            EXPECT_NEAR(s->weight(), 1.0f, 1e-4f);
            EXPECT_NEAR(p->eval(vec3(0.0f), wo, s->wi), p->eval(vec3(0.0f), s->wi, wo), 1e-5f * s->p);
        }
    }
}

TEST(PhaseFunctions, HenyeyGreensteinMeanCosineIsG) {
    // ⟨cos θ⟩ = g (Henyey & Greenstein 1941), by the samples' mean with its standard error.
    for (const float g : {-0.6f, 0.0f, 0.4f, 0.8f}) {
        const auto p = makePhase("hg", {{"g", g}});
        const vec3 wo(0, 0, 1);
        Pcg32 rng(9, 1);
        double s = 0, s2 = 0;
        const int n = 200000;
        for (int i = 0; i < n; ++i) {
            const double mu = -glm::dot(wo, p->sample(vec3(0.0f), wo, vec2(rng.uniform(), rng.uniform()))->wi);
            s += mu;
            s2 += mu * mu;
        }
        const double mean = s / n, se = std::sqrt((s2 / n - mean * mean) / n);
        EXPECT_NEAR(mean, g, 5 * se + 1e-4) << "g=" << g;
    }
    // g > 0 scatters forward: wi near −wo (the ray goes on) is the most likely direction.
    const auto fwd = makePhase("hg", {{"g", 0.7f}});
    const vec3 wo(0, 0, 1);
    EXPECT_GT(fwd->eval(vec3(0.0f), wo, -wo), 10 * fwd->eval(vec3(0.0f), wo, wo));
}

TEST(PhaseFunctions, RayleighClosedForm) {
    const auto p = makePhase("rayleigh");
    const vec3 wo(0, 0, 1);
    EXPECT_NEAR(p->eval(vec3(0.0f), wo, -wo), 6.0 / (16.0 * M_PI), 1e-6);  // cos θ = 1
    EXPECT_NEAR(p->eval(vec3(0.0f), wo, vec3(1, 0, 0)), 3.0 / (16.0 * M_PI), 1e-6);  // cos θ = 0
    EXPECT_NEAR(p->eval(vec3(0.0f), wo, wo), 6.0 / (16.0 * M_PI), 1e-6);  // backward = forward
    // The sampled cosine's CDF (μ³ + 3μ + 4)/8 at a few points (Frisvad 2011).
    for (const float u : {0.0f, 0.1f, 0.5f, 0.9f, 0.999f}) {
        const float mu = -glm::dot(wo, p->sample(vec3(0.0f), wo, vec2(u, 0.3f))->wi);
        EXPECT_NEAR((mu * mu * mu + 3 * mu + 4) / 8, u, 1e-5f) << u;
    }
}

TEST(PhaseFunctions, BadParametersAreLocated) {
    for (const float g : {1.0f, -1.0f, 1.5f}) {
        try {
            makePhase("hg", {{"g", g}});
            ADD_FAILURE() << "g = " << g << " accepted";
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find("must lie in (-1, 1)"), std::string::npos) << e.what();
        }
    }
    EXPECT_THROW(makePhase("isotropic", {{"g", 0.5f}}), Error);  // unknown parameter
    EXPECT_THROW(makePhase("schlick"), Error);                    // unknown type
}
