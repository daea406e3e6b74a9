// Fresnel edge cases and cross-checks (materials/fresnel.h).
#include <gtest/gtest.h>

#include "core/rng.h"
#include "materials/fresnel.h"

using namespace iris;

TEST(Fresnel, DielectricNormalIncidence) {
    for (float eta : {1.0001f, 1.33f, 1.5f, 2.4f, 0.5f}) {
        const float expect = sqr((eta - 1) / (eta + 1));
        EXPECT_NEAR(fresnelDielectric(1.0f, eta), expect, 1e-6f) << eta;
        // From the inside at normal incidence the relative index is 1/eta: same value.
        EXPECT_NEAR(fresnelDielectric(-1.0f, eta), expect, 1e-6f) << eta;
        EXPECT_NEAR(schlickF0FromEta(eta), expect, 1e-7f);
    }
}

TEST(Fresnel, DielectricTotalInternalReflection) {
    const float eta = 1.5f;
    const float cosCritical = std::sqrt(1.0f - 1.0f / (eta * eta));  // sinθc = 1/η
    EXPECT_EQ(fresnelDielectric(-(cosCritical - 1e-3f), eta), 1.0f);
    EXPECT_EQ(fresnelDielectric(-0.01f, eta), 1.0f);
    EXPECT_LT(fresnelDielectric(-(cosCritical + 1e-2f), eta), 1.0f);
    const auto r = fresnelDielectricFull(-0.1f, eta);
    EXPECT_EQ(r.R, 1.0f);
    EXPECT_EQ(r.cosThetaT, 0.0f);
    // Grazing from outside: R → 1.
    EXPECT_NEAR(fresnelDielectric(1e-6f, eta), 1.0f, 1e-4f);
}

TEST(Fresnel, DielectricSnellAndReciprocity) {
    Pcg32 rng(1, 1);
    for (int i = 0; i < 1000; ++i) {
        const float ci = 0.01f + 0.99f * rng.uniform();
        const float eta = 1.01f + 1.5f * rng.uniform();
        const auto out = fresnelDielectricFull(ci, eta);
        ASSERT_LT(out.cosThetaT, 0.0f);
        // Snell: sinθi = η sinθt.
        EXPECT_NEAR(std::sqrt(1 - ci * ci), eta * std::sqrt(1 - sqr(out.cosThetaT)), 1e-4f);
        // The reverse path (from inside at θt) has the same reflectance.
        const auto back = fresnelDielectricFull(out.cosThetaT, eta);
        // float round-off in cosθt near the critical angle: relative tolerance on 1 − R.
        EXPECT_NEAR(back.R, out.R, 2e-5f + 2e-3f * (1 - out.R) + 2e-4f * out.R);
        EXPECT_NEAR(back.cosThetaT, ci, 1e-4f);
        EXPECT_FLOAT_EQ(back.etaIT, 1.0f / eta);
        // The thesis' form (eqs. 2.8–2.9, Walter 2007 eq. 22) agrees with the r⊥/r∥ form.
        EXPECT_NEAR(fresnelDielectricWalter(ci, eta), out.R, 2e-5f);
        // A refracted direction is a unit vector on the other side.
        const vec3 w(std::sqrt(1 - ci * ci), 0, ci);
        const vec3 t = refractLocal(w, out.cosThetaT, out.etaTI);
        EXPECT_NEAR(glm::length(t), 1.0f, 1e-4f);
        const vec3 t2 = refract(w, vec3(0, 0, 1), out.cosThetaT, out.etaTI);
        EXPECT_NEAR(glm::length(t - t2), 0.0f, 1e-5f);
    }
}

TEST(Fresnel, ConductorWithZeroKEqualsDielectric) {
    for (float eta : {1.2f, 1.5f, 2.0f, 3.0f})
        for (float c = 0.0f; c <= 1.0f; c += 0.05f)
            EXPECT_NEAR(fresnelConductor(c, eta, 0.0f), fresnelDielectric(c, eta), 1e-5f) << eta << " " << c;
}

TEST(Fresnel, ConductorNormalIncidenceAndLimits) {
    // ((n−1)² + k²) / ((n+1)² + k²) at normal incidence (pbrt-v4 §9.3.6).
    const float n = 0.155f, k = 3.6f;  // approximately silver at 550 nm
    EXPECT_NEAR(fresnelConductor(1.0f, n, k), (sqr(n - 1) + k * k) / (sqr(n + 1) + k * k), 1e-5f);
    EXPECT_NEAR(fresnelConductor(0.0f, n, k), 1.0f, 1e-5f);
    for (float c = 0.0f; c <= 1.0f; c += 0.01f) {
        const float f = fresnelConductor(c, n, k);
        EXPECT_GE(f, 0.0f);
        EXPECT_LE(f, 1.0f);
    }
    // Large k → perfect mirror.
    EXPECT_NEAR(fresnelConductor(0.5f, 1.0f, 1e4f), 1.0f, 1e-3f);
}

TEST(Fresnel, Schlick) {
    EXPECT_FLOAT_EQ(fresnelSchlick(1.0f, 0.04f), 0.04f);
    EXPECT_FLOAT_EQ(fresnelSchlick(0.0f, 0.04f), 1.0f);
    // Schlick's approximation error for η = 1.5: below 0.02 for cosθ ≥ 0.2, below 0.04 at grazing
    // angles (it overestimates there).
    for (float c = 0.0f; c <= 1.0f; c += 0.05f)
        EXPECT_NEAR(fresnelSchlick(c, schlickF0FromEta(1.5f)), fresnelDielectric(c, 1.5f), c >= 0.2f ? 0.02f : 0.04f) << c;
}

TEST(Fresnel, SpectrumOverloadsMatchScalar) {
    SampledSpectrum eta(4), k(4), f0(4);
    for (int i = 0; i < 4; ++i) {
        eta[i] = 1.3f + 0.2f * i;
        k[i] = 0.5f * i;
        f0[i] = 0.1f * i;
    }
    const auto d = fresnelDielectric(0.3f, eta);
    const auto c = fresnelConductor(0.3f, eta, k);
    const auto s = fresnelSchlick(0.3f, f0);
    for (int i = 0; i < 4; ++i) {
        EXPECT_EQ(d[i], fresnelDielectric(0.3f, eta[i]));
        EXPECT_EQ(c[i], fresnelConductor(0.3f, eta[i], k[i]));
        EXPECT_EQ(s[i], fresnelSchlick(0.3f, f0[i]));
    }
}
