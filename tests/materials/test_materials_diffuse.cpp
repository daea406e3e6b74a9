// The diffuse example plugin through the shared BSDF harness.
#include <gtest/gtest.h>

#include "tests/support/bsdf_test_util.h"

using namespace iris;
using namespace iris::test;

TEST(MaterialsDiffuse, ChiSquareAndConsistency) {
    auto inst = makeBSDF("diffuse", {{"reflectance", 0.7f}});
    Chi2Options opt;
    opt.numTests = 3;
    for (float co : {1.0f, 0.5f, 0.05f}) {
        const vec3 wo = dirFromCos(co, 0.3f);
        const auto r = chi2Test(*inst.bsdf, wo, opt);
        EXPECT_TRUE(r.passed) << r.message;
        EXPECT_NEAR(r.pdfMass, 1.0, 1e-3);
        const auto c = checkConsistency(*inst.bsdf, wo);
        EXPECT_EQ(c.invalid, 0);
        EXPECT_LT(c.maxRelErrF, 1e-5f) << c.message;
        EXPECT_LT(c.maxRelErrPdf, 1e-5f) << c.message;
        const auto pi = pdfIntegral(*inst.bsdf, wo);
        EXPECT_LT(pi.mean, 1.0 + 4 * pi.stderr_);
        EXPECT_GT(pi.mean, 1.0 - 4 * pi.stderr_);
        for (const auto& a : albedo(*inst.bsdf, wo)) EXPECT_NEAR(a.mean, 0.7, 1e-4);  // weight is exactly ρ
    }
    EXPECT_LT(reciprocityError(*inst.bsdf), 1e-6f);
    EXPECT_EQ(inst.bsdf->eval(dirFromCos(-0.5f), dirFromCos(0.5f), TransportMode::Radiance).maxValue(), 0.0f);
}

TEST(MaterialsDiffuse, HarnessRejectsUnknownParameter) {
    EXPECT_THROW(makeBSDF("diffuse", {{"reflectanse", 0.7f}}), Error);
}
