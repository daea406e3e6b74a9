// Phase functions as Mueller matrices (polarized mode, docs/polarization.md): Rayleigh's
// scattering matrix (media/phase/rayleigh.cpp; Chandrasekhar 1960 §I.17, Hansen & Travis 1974
// eq. 2.15) — its (0, 0) entry is the scalar phase function, unpolarized light scattered at 90°
// leaves fully polarized normal to the plane of scattering (checked in the implicit Stokes bases,
// so a wrong basis rotation fails), forward scattering does not polarize, it keeps Stokes vectors
// in the cone; the depolarizing default of the other phase functions; blendphase's weighted sum.
#include <gtest/gtest.h>

#include "core/rng.h"
#include "core/sampling.h"
#include "spectral/stokes_basis.h"
#include "tests/support/phase_test_util.h"

using namespace iris;
using iris::test::makePhase;

namespace {

constexpr int kN = 3;
const vec3 kX(0.3f, -0.2f, 0.1f);

vec3 randomDir(Pcg32& rng) { return sampleUniformSphere(vec2(rng.uniform(), rng.uniform())); }

/// A unit vector orthogonal to d.
vec3 orthogonalTo(const vec3& d, Pcg32& rng) {
    for (;;) {
        const vec3 c = glm::cross(d, randomDir(rng));
        if (glm::dot(c, c) > 1e-3f) return glm::normalize(c);
    }
}

StokesVector unpolarized() { return StokesVector::unpolarized(SampledSpectrum(kN, 1.0f)); }

}  // namespace

TEST(PhaseMueller, RayleighIntensityEntryIsTheScalarPhaseFunction) {
    const auto p = makePhase("rayleigh");
    Pcg32 rng(11, 5);
    for (int i = 0; i < 500; ++i) {
        const vec3 wo = randomDir(rng), wi = randomDir(rng);
        const MuellerSpectrum M = p->evalMueller(kX, wo, wi, kN).expanded();
        const float ref = p->eval(kX, wo, wi);
        for (int k = 0; k < kN; ++k) ASSERT_NEAR(M(0, 0)[k], ref, 1e-6f * ref) << i;
        const StokesVector out = M * unpolarized();
        EXPECT_NEAR(out.s[0][0], ref, 1e-6f * ref);  // unpolarized light: S0 out = p (spectral mode)
    }
}

TEST(PhaseMueller, RayleighAt90DegreesPolarizesNormalToThePlaneOfScattering) {
    const auto p = makePhase("rayleigh");
    Pcg32 rng(3, 9);
    for (int i = 0; i < 300; ++i) {
        const vec3 wo = randomDir(rng);
        const vec3 wi = orthogonalTo(wo, rng);  // cos θ = −wo·wi = 0
        const StokesVector out = p->evalMueller(kX, wo, wi, kN) * unpolarized();
        const double s0 = out.s[0][0], s1 = out.s[1][0], s2 = out.s[2][0], s3 = out.s[3][0];
        EXPECT_NEAR(s0, 3.0 / (16.0 * kPi), 1e-6);
        EXPECT_NEAR(std::sqrt(s1 * s1 + s2 * s2 + s3 * s3) / s0, 1.0, 1e-5) << i;  // fully polarized
        EXPECT_NEAR(s3, 0.0, 1e-7);                                                  // linearly
        // The electric field is along n, the normal of the plane of (wi, wo). In the implicit
        // basis x = stokesBasis(wo) with y = wo × x (x turned by +90° seen looking back along the
        // beam, spectral/mueller.h), a field at angle φ from x has S1 = S0 cos 2φ, S2 = S0 sin 2φ.
        const vec3 n = glm::normalize(glm::cross(wi, wo)), x = stokesBasis(wo), y = glm::cross(wo, x);
        const double c = glm::dot(n, x), s = glm::dot(n, y);
        EXPECT_NEAR(s1 / s0, c * c - s * s, 1e-4) << i;
        EXPECT_NEAR(s2 / s0, 2 * c * s, 1e-4) << i;
    }
}

TEST(PhaseMueller, RayleighForwardScatteringDoesNotPolarizeAndBackscatteringMirrors) {
    const auto p = makePhase("rayleigh");
    Pcg32 rng(4, 4);
    for (int i = 0; i < 100; ++i) {
        const vec3 wo = randomDir(rng);
        const MuellerSpectrum F = p->evalMueller(kX, wo, -wo, kN).expanded();  // θ = 0: wi = −wo
        const float pf = 3.0f / (8.0f * kPi);
        for (int r = 0; r < 4; ++r)
            for (int c = 0; c < 4; ++c) ASSERT_NEAR(F(r, c)[0], r == c ? pf : 0.0f, 1e-6f) << i << " " << r << c;
        // θ = π: the degree of polarization is kept, the handedness of circular light flips.
        const MuellerSpectrum B = p->evalMueller(kX, wo, wo, kN).expanded();
        StokesVector circ = unpolarized();
        circ.s[3] = SampledSpectrum(kN, 1.0f);
        const StokesVector out = B * circ;
        EXPECT_NEAR(out.s[0][0], pf, 1e-6f);
        EXPECT_NEAR(out.s[3][0], -pf, 1e-6f);
    }
}

TEST(PhaseMueller, RayleighKeepsStokesVectorsInTheCone) {
    const auto p = makePhase("rayleigh");
    Pcg32 rng(8, 1);
    for (int i = 0; i < 2000; ++i) {
        const vec3 wo = randomDir(rng), wi = randomDir(rng);
        // A random fully polarized input (a point of the Poincaré sphere).
        const vec3 q = randomDir(rng);
        StokesVector in = unpolarized();
        for (int k = 0; k < 3; ++k) in.s[k + 1] = SampledSpectrum(kN, q[k]);
        const StokesVector out = p->evalMueller(kX, wo, wi, kN) * in;
        const double s0 = out.s[0][0], pol = std::sqrt(double(out.s[1][0]) * out.s[1][0] + double(out.s[2][0]) * out.s[2][0] +
                                                       double(out.s[3][0]) * out.s[3][0]);
        EXPECT_GE(s0, -1e-7);
        EXPECT_LE(pol, s0 * (1 + 1e-5) + 1e-7) << i;
    }
}

TEST(PhaseMueller, UnpolarizedPhaseFunctionsAreDepolarizers) {
    for (const char* type : {"isotropic", "hg"}) {
        const auto p = makePhase(type);
        const vec3 wo = glm::normalize(vec3(0.2f, 0.5f, 0.8f)), wi = glm::normalize(vec3(-0.6f, 0.1f, 0.3f));
        const MuellerSpectrum M = p->evalMueller(kX, wo, wi, kN);
        EXPECT_TRUE(M.depolarizing()) << type;
        EXPECT_FLOAT_EQ(M(0, 0)[1], p->eval(kX, wo, wi)) << type;
    }
}

TEST(PhaseMueller, BlendphaseBlendsTheNestedMatrices) {
    const auto blend = test::phaseFromXml(
        R"(<phase type="blendphase"><float name="weight" value="0.25"/><phase type="isotropic"/><phase type="rayleigh"/></phase>)");
    const auto iso = makePhase("isotropic"), ray = makePhase("rayleigh");
    Pcg32 rng(5, 2);
    for (int i = 0; i < 100; ++i) {
        const vec3 wo = randomDir(rng), wi = randomDir(rng);
        const MuellerSpectrum B = blend->evalMueller(kX, wo, wi, kN).expanded();
        const MuellerSpectrum I = iso->evalMueller(kX, wo, wi, kN).expanded(), R = ray->evalMueller(kX, wo, wi, kN).expanded();
        for (int r = 0; r < 4; ++r)
            for (int c = 0; c < 4; ++c) ASSERT_NEAR(B(r, c)[0], 0.75f * I(r, c)[0] + 0.25f * R(r, c)[0], 1e-6f) << i;
        EXPECT_NEAR(B(0, 0)[0], blend->eval(kX, wo, wi), 1e-6f);
    }
}
