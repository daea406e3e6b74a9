// The tabphase phase function (media/phase/tabphase.cpp) against closed forms: a constant
// table is isotropic, the table (0, 1) is p = (1 + μ)/(4π) with mean cosine 1/3, a finely
// tabulated Henyey–Greenstein equals hg within the linear interpolation's error, ∫p = 1, χ² of its
// samples against its pdf, and located errors for bad tables.
#include <gtest/gtest.h>

#include <sstream>

#include "core/rng.h"
#include "core/sampling.h"
#include "tests/support/error_of.h"
#include "tests/support/phase_test_util.h"

using namespace iris;
using namespace iris::test;

namespace {

const vec3 kX(0.0f);

std::shared_ptr<PhaseFunction> table(const std::string& values) { return makePhase("tabphase", {{"values", values}}); }

}  // namespace

TEST(PhaseTabulated, ConstantTableIsIsotropic) {
    for (const char* values : {"1, 1", "2 2 2 2", "0.5,0.5,0.5"}) {
        const auto p = table(values);
        Pcg32 rng(1, 1);
        for (int i = 0; i < 200; ++i) {
            const vec3 wo = sampleUniformSphere(vec2(rng.uniform(), rng.uniform()));
            const vec3 wi = sampleUniformSphere(vec2(rng.uniform(), rng.uniform()));
            EXPECT_NEAR(p->eval(kX, wo, wi), kInv4Pi, 1e-6f) << values;
        }
    }
}

TEST(PhaseTabulated, LinearTableClosedForm) {
    // f(μ) = (1 + μ)/2 integrates to 1 over [−1, 1]: p = (1 + μ)/(4π), ⟨μ⟩ = ∫ μ (1 + μ)/2 dμ = 1/3.
    const auto p = table("0, 1");
    const vec3 wo(0, 0, 1);
    for (const float mu : {-1.0f, -0.5f, 0.0f, 0.3f, 1.0f}) {
        const vec3 wi = -vec3(std::sqrt(1 - mu * mu), 0, mu);  // −wo·wi = μ
        EXPECT_NEAR(p->eval(kX, wo, wi), (1 + mu) * kInv4Pi, 1e-6f) << mu;
    }
    Pcg32 rng(3, 1);
    const int n = 200000;
    double s = 0, s2 = 0;
    for (int i = 0; i < n; ++i) {
        const double mu = -glm::dot(wo, p->sample(kX, wo, vec2(rng.uniform(), rng.uniform()))->wi);
        s += mu;
        s2 += mu * mu;
    }
    const double mean = s / n, se = std::sqrt((s2 / n - mean * mean) / n);
    EXPECT_NEAR(mean, 1.0 / 3.0, 5 * se);
    EXPECT_GT(std::abs(mean - 0.3), 5 * se);  // the test tells 1/3 from a nearby value
}

TEST(PhaseTabulated, FinelyTabulatedHenyeyGreensteinIsHg) {
    // 2001 samples of hg(g = 0.5) over μ: linear interpolation errs by at most h²/8·max|f''|
    // (h = 0.001, f'' ≤ 6 at μ = 1 for g = 0.5: 8e-7 absolute on values ≥ 0.02), normalisation by the
    // trapezoid rule by the same order: 1e-4 relative covers both.
    const auto hg = makePhase("hg", {{"g", 0.5f}});
    std::ostringstream values;
    for (int i = 0; i <= 2000; ++i) {
        const float mu = -1.0f + float(i) / 1000.0f;
        values << (i ? ", " : "") << hg->eval(kX, vec3(0, 0, 1), -vec3(std::sqrt(std::max(0.0f, 1 - mu * mu)), 0, mu)) * 4 * kPi;
    }
    const auto p = table(values.str());
    Pcg32 rng(6, 2);
    for (int i = 0; i < 1000; ++i) {
        const vec3 wo = sampleUniformSphere(vec2(rng.uniform(), rng.uniform()));
        const vec3 wi = sampleUniformSphere(vec2(rng.uniform(), rng.uniform()));
        const float want = hg->eval(kX, wo, wi);
        EXPECT_NEAR(p->eval(kX, wo, wi), want, 1e-4f * want);
    }
}

TEST(PhaseTabulated, NormalisedAndSampledByItsPdf) {
    const auto p = table("0.1, 2, 0.5, 0, 3");
    for (const vec3& wo : {vec3(0, 0, 1), glm::normalize(vec3(0.4f, 0.3f, -0.6f))}) expectNormalisedAndSampledByItsPdf(*p, kX, wo, 2);
    // A table sampled as another one is rejected.
    EXPECT_FALSE(chi2Test(PhaseAsBSDF(*table("0.1, 2, 0.6, 0, 3"), kX, p.get()), vec3(0, 0, 1)).passed);
}

TEST(PhaseTabulated, BadTablesAreRefusedWithTheirLine) {
    auto err = [](const std::string& values) {
        return errorOf([&] { phaseFromXml("<phase type=\"tabphase\">\n<string name=\"values\" value=\"" + values + "\"/></phase>"); });
    };
    EXPECT_TRUE(contains(err("1"), "<string>:3: tabphase: values needs at least 2 entries, got 1"));
    EXPECT_TRUE(contains(err("1, x"), "<string>:3: tabphase: 'x' in values is not a number"));
    EXPECT_TRUE(contains(err("1, 2q"), "'2q' in values is not a number"));
    EXPECT_TRUE(contains(err("1, -2"), "<string>:3: tabphase: value 1 is -2 (values must be finite and >= 0)"));
    EXPECT_TRUE(contains(err("1, inf"), "value 1 is inf"));
    EXPECT_TRUE(contains(err("0, 0, 0"), "<string>:3: tabphase: the values are all 0"));
    EXPECT_TRUE(contains(errorOf([] { phaseFromXml("<phase type=\"tabphase\"/>"); }), "<string>:2: phase 'tabphase': missing required parameter 'values'"));
}
