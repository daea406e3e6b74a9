// The blendphase phase function (media/phase/blendphase.cpp): the weighted sum of its two
// nested phase functions in Mitsuba's order, w = 0 and 1 giving each alone, ∫p = 1, χ² of its
// samples against its pdf, a weight grid looked up at the scattering point, and located errors.
#include <gtest/gtest.h>

#include "core/rng.h"
#include "core/sampling.h"
#include "tests/support/error_of.h"
#include "tests/support/phase_test_util.h"
#include "tests/support/vol_file.h"

using namespace iris;
using namespace iris::test;

namespace {

const vec3 kX(0.0f);

std::string blend(const std::string& weight, const std::string& nested) {
    return "<phase type=\"blendphase\">" + weight + nested + "</phase>";
}
const std::string kIsoHg = "<phase type=\"isotropic\"/><phase type=\"hg\"><float name=\"g\" value=\"0.6\"/></phase>";

/// The largest |a − b| / b over random direction pairs.
float largestDifference(const PhaseFunction& a, const PhaseFunction& b, const vec3& xa = kX) {
    Pcg32 rng(2, 3);
    float worst = 0.0f;
    for (int i = 0; i < 500; ++i) {
        const vec3 wo = sampleUniformSphere(vec2(rng.uniform(), rng.uniform()));
        const vec3 wi = sampleUniformSphere(vec2(rng.uniform(), rng.uniform()));
        const float pb = b.eval(kX, wo, wi);
        worst = std::max(worst, std::abs(a.eval(xa, wo, wi) - pb) / pb);
        worst = std::max(worst, std::abs(a.pdf(xa, wo, wi) - b.pdf(kX, wo, wi)) / pb);
    }
    return worst;
}

}  // namespace

TEST(PhaseBlend, IsTheWeightedSumOfItsPhasesInMitsubasOrder) {
    const auto iso = makePhase("isotropic"), hg = makePhase("hg", {{"g", 0.6f}});
    const auto p = phaseFromXml(blend("<float name=\"weight\" value=\"0.3\"/>", kIsoHg));
    Pcg32 rng(5, 6);
    for (int i = 0; i < 500; ++i) {
        const vec3 wo = sampleUniformSphere(vec2(rng.uniform(), rng.uniform()));
        const vec3 wi = sampleUniformSphere(vec2(rng.uniform(), rng.uniform()));
        const float want = 0.7f * iso->eval(kX, wo, wi) + 0.3f * hg->eval(kX, wo, wi);
        EXPECT_NEAR(p->eval(kX, wo, wi), want, 1e-6f * want);
    }
    EXPECT_EQ(largestDifference(*phaseFromXml(blend("<float name=\"weight\" value=\"0\"/>", kIsoHg)), *iso), 0.0f);
    EXPECT_EQ(largestDifference(*phaseFromXml(blend("<float name=\"weight\" value=\"1\"/>", kIsoHg)), *hg), 0.0f);
    // Named phases come in the alphanumeric order of their names: 'a' (hg) is the first.
    const auto named = phaseFromXml(blend("<float name=\"weight\" value=\"0\"/>",
                                          "<phase name=\"b\" type=\"isotropic\"/><phase name=\"a\" type=\"hg\">"
                                          "<float name=\"g\" value=\"0.6\"/></phase>"));
    EXPECT_EQ(largestDifference(*named, *hg), 0.0f);
    EXPECT_GT(largestDifference(*named, *iso), 0.5f);  // the comparison can fail
}

TEST(PhaseBlend, NormalisedAndSampledByItsPdf) {
    const auto p = phaseFromXml(blend("<float name=\"weight\" value=\"0.4\"/>", kIsoHg));
    for (const vec3& wo : {vec3(0, 0, 1), glm::normalize(vec3(0.5f, -0.2f, -0.8f))}) expectNormalisedAndSampledByItsPdf(*p, kX, wo, 3);
}

TEST(PhaseBlend, WeightGridIsLookedUpAtTheScatteringPoint) {
    // Weights 0 and 1 at the voxel centres x = 1/4 and 3/4, 0.5 half way.
    const std::string f = writeVolFile("iris_phase_blend", "w.vol", ivec3(2, 1, 1), 1, {0, 1});
    const auto p = phaseFromXml(blend("<volume type=\"gridvolume\" name=\"weight\"><string name=\"filename\" value=\"" + f +
                                          "\"/></volume>",
                                      kIsoHg));
    const auto iso = makePhase("isotropic"), hg = makePhase("hg", {{"g", 0.6f}});
    const auto half = phaseFromXml(blend("<float name=\"weight\" value=\"0.5\"/>", kIsoHg));
    EXPECT_LT(largestDifference(*p, *iso, vec3(0.25f, 0.5f, 0.5f)), 1e-6f);
    EXPECT_LT(largestDifference(*p, *hg, vec3(0.75f, 0.5f, 0.5f)), 1e-6f);
    EXPECT_LT(largestDifference(*p, *half, vec3(0.5f, 0.5f, 0.5f)), 1e-6f);
    expectNormalisedAndSampledByItsPdf(*p, vec3(0.6f, 0.5f, 0.5f), vec3(0, 0, 1), 3);
}

TEST(PhaseBlend, BadInputIsRefusedWithItsLine) {
    EXPECT_TRUE(contains(errorOf([] { phaseFromXml("<phase type=\"blendphase\"><phase type=\"isotropic\"/></phase>"); }),
                         "<string>:2: blendphase: needs exactly two nested <phase>s, got 1"));
    EXPECT_TRUE(contains(errorOf([] { phaseFromXml(blend("", kIsoHg + "<phase type=\"rayleigh\"/>")); }), "got 3"));
    EXPECT_TRUE(contains(errorOf([] { phaseFromXml(blend("\n<float name=\"weight\" value=\"1.5\"/>", kIsoHg)); }),
                         "<string>:3: blendphase: weight = 1.5 must lie in [0, 1]"));
    EXPECT_TRUE(contains(errorOf([] {
                             phaseFromXml(blend("\n<volume type=\"constvolume\" name=\"weight\"><rgb name=\"value\" value=\"0.1, 0.2, 0.3\"/>"
                                                "</volume>",
                                                kIsoHg));
                         }),
                         "<string>:3: parameter 'weight' must be a volume of 1 channel, this constvolume has 3"));
}
