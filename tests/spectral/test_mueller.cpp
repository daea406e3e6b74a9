// Mueller calculus and Stokes bases (spectral/mueller.h, spectral/stokes_basis.h): the conventions
// of Mitsuba 3's mueller.h and the physics of ideal elements (Collett, "Polarized Light"; Malus's
// law), each element as a 4×4 real matrix.
#include <gtest/gtest.h>

#include <functional>
#include <random>

#include "spectral/mueller.h"
#include "spectral/stokes_basis.h"

using namespace iris;

namespace {

using Stokes4 = std::array<float, 4>;

Stokes4 through(const Mueller4f& m, const Stokes4& s) {
    Stokes4 r{};
    for (int i = 0; i < 4; ++i)
        for (int k = 0; k < 4; ++k) r[size_t(i)] += m.m[i][k] * s[size_t(k)];
    return r;
}

void expectStokes(const Stokes4& got, const Stokes4& want, float tol = 1e-6f) {
    for (int i = 0; i < 4; ++i) EXPECT_NEAR(got[size_t(i)], want[size_t(i)], tol) << "component " << i;
}

const Stokes4 kUnpolarized{1, 0, 0, 0};

using RotationRule = std::function<mueller::BasisRotation(const vec3&, const vec3&, const vec3&)>;

/// Mitsuba 3's documented examples of a change of Stokes basis (mueller.h, rotate_stokes_basis and
/// rotator): horizontal light (1, 1, 0, 0) in the basis (1, 0, 0) travelling along +z is +45°
/// light (1, 0, 1, 0) in the basis (1, −1, 0)/√2; and a +45° rotator turns (1, 1, 0, 0) into
/// (1, 0, −1, 0). True when `rule` reproduces both.
bool rotationConventionHolds(const RotationRule& rule) {
    const vec3 forward(0, 0, 1), from(1, 0, 0), to = glm::normalize(vec3(1, -1, 0));
    const Stokes4 a = through(mueller::rotator(rule(forward, from, to)), {1, 1, 0, 0});
    const Stokes4 b = through(mueller::rotator(mueller::BasisRotation::ofAngle(kPi / 4)), {1, 1, 0, 0});
    auto near = [](const Stokes4& x, const Stokes4& y) {
        for (int i = 0; i < 4; ++i)
            if (std::abs(x[size_t(i)] - y[size_t(i)]) > 1e-5f) return false;
        return true;
    };
    return near(a, {1, 0, 1, 0}) && near(b, {1, 0, -1, 0});
}

}  // namespace

TEST(Mueller, BasisRotationFollowsMitsubasConvention) {
    EXPECT_TRUE(rotationConventionHolds(stokesBasisRotation));
}

TEST(Mueller, AWrongBasisRotationFailsTheConventionCheck) {
    // The check has power: the rotation of the opposite sense (the transposed rotator), and the
    // angle instead of twice the angle, are both caught.
    const RotationRule oppositeSense = [](const vec3& f, const vec3& a, const vec3& b) {
        const mueller::BasisRotation r = stokesBasisRotation(f, a, b);
        return mueller::BasisRotation{r.c2, -r.s2};
    };
    const RotationRule singleAngle = [](const vec3& f, const vec3& a, const vec3& b) {
        const float theta = std::atan2(glm::dot(f, glm::cross(a, b)), glm::dot(a, b));
        return mueller::BasisRotation{std::cos(theta), std::sin(theta)};
    };
    EXPECT_FALSE(rotationConventionHolds(oppositeSense));
    EXPECT_FALSE(rotationConventionHolds(singleAngle));
}

TEST(Mueller, StokesBasisIsOrthogonalToTheDirectionAndUnit) {
    for (const vec3& d : {vec3(0, 0, 1), vec3(0, 0, -1), glm::normalize(vec3(1, 2, 3)), glm::normalize(vec3(-3, 0.5f, -0.2f))}) {
        const vec3 b = stokesBasis(d);
        EXPECT_NEAR(glm::dot(b, d), 0.0f, 1e-6f);
        EXPECT_NEAR(glm::length(b), 1.0f, 1e-6f);
    }
}

TEST(Mueller, MalusLawThroughARotatedPolarizer) {
    // Unpolarized light through a polarizer at 0°, then one at θ: I = ½ cos²θ (Malus 1809).
    for (float deg : {0.0f, 15.0f, 30.0f, 45.0f, 60.0f, 75.0f, 90.0f, 135.0f}) {
        const float t = deg * kPi / 180;
        const Mueller4f second = mueller::rotatedElement(t, mueller::linearPolarizer());
        const Stokes4 out = through(second, through(mueller::linearPolarizer(), kUnpolarized));
        EXPECT_NEAR(out[0], 0.5f * std::cos(t) * std::cos(t), 1e-6f) << deg;
    }
}

TEST(Mueller, CrossedPolarizersTransmitNothing) {
    const Stokes4 out = through(mueller::rotatedElement(kPi / 2, mueller::linearPolarizer()), through(mueller::linearPolarizer(), kUnpolarized));
    expectStokes(out, {0, 0, 0, 0});
    // A third polarizer at 45° between them lets ⅛ through.
    const Stokes4 mid = through(mueller::rotatedElement(kPi / 4, mueller::linearPolarizer()), through(mueller::linearPolarizer(), kUnpolarized));
    EXPECT_NEAR(through(mueller::rotatedElement(kPi / 2, mueller::linearPolarizer()), mid)[0], 0.125f, 1e-6f);
}

TEST(Mueller, QuarterWavePlateTurnsDiagonalIntoCircularLight) {
    // Current Mitsuba 3 test_retarder.py test02 (after Goldstein, "Polarized Light", 3rd ed.,
    // eqs. 6.46-6.47; the first edition by Collett had the fast and slow axes the other way): a
    // quarter-wave plate with its fast axis at 0° turns +45° linear light into left circular
    // (S3 = −S0), −45° into right circular (S3 = +S0); right circular into +45° light.
    const Mueller4f qwp = mueller::linearRetarder(kPi / 2);
    expectStokes(through(qwp, {1, 0, 1, 0}), {1, 0, 0, -1});
    expectStokes(through(qwp, {1, 0, -1, 0}), {1, 0, 0, 1});
    expectStokes(through(qwp, {1, 0, 0, 1}), {1, 0, 1, 0});
    expectStokes(through(qwp, {1, 0, 0, -1}), {1, 0, -1, 0});
    // A half-wave plate swaps the diagonals and the circular senses (test03).
    const Mueller4f hwp = mueller::linearRetarder(kPi);
    expectStokes(through(hwp, {1, 0, 1, 0}), {1, 0, -1, 0});
    expectStokes(through(hwp, {1, 0, 0, 1}), {1, 0, 0, -1});
}

TEST(Mueller, CircularPolarizersPassOneSenseOnly) {
    expectStokes(through(mueller::rightCircularPolarizer(), kUnpolarized), {0.5f, 0, 0, 0.5f});
    expectStokes(through(mueller::leftCircularPolarizer(), kUnpolarized), {0.5f, 0, 0, -0.5f});
    expectStokes(through(mueller::leftCircularPolarizer(), {1, 0, 0, 1}), {0, 0, 0, 0});
}

TEST(Mueller, RotateBasesEqualsTheMatrixProducts) {
    // rotateBases(M, in, out) = R_out · M · R_inᵀ, lane by lane.
    MuellerSpectrum M(4);
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            for (int l = 0; l < 4; ++l) M(i, j)[l] = float(1 + i + 2 * j) * (l + 1) * (i == j ? 1.0f : 0.3f);
    const auto in = mueller::BasisRotation::ofAngle(0.3f), out = mueller::BasisRotation::ofAngle(-1.1f);
    const MuellerSpectrum r = mueller::rotateBases(M, in, out);
    const Mueller4f Ro = mueller::rotator(out), RiT = mueller::rotator({in.c2, -in.s2});
    for (int l = 0; l < 4; ++l) {
        Mueller4f m;
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j) m.m[i][j] = M(i, j)[l];
        const Mueller4f want = mueller::multiply(Ro, mueller::multiply(m, RiT));
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j) EXPECT_NEAR(r(i, j)[l], want.m[i][j], 1e-5f);
    }
}

// The interface layout's rotation (mueller::rotatedInterface, what rotateBases takes for it) against
// the dense R_out · M · R_inᵀ (rotateBasesDense) on random entries and rotations: the same value in
// every entry and lane (== : equal up to the sign of a zero).
TEST(Mueller, RotatedInterfaceEqualsTheDenseRotation) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u(-1, 1);
    for (int trial = 0; trial < 2000; ++trial) {
        const int n = 1 + trial % 9;
        auto random = [&] { return SampledSpectrum::fromLanes(n, [&](int) { return u(rng); }); };
        const MuellerSpectrum M = mueller::interfaceMueller(random(), random(), random(), random());
        ASSERT_TRUE(M.interfaceLayout());
        const auto in = trial % 7 == 0 ? mueller::BasisRotation{} : mueller::BasisRotation::ofAngle(4 * u(rng));
        const auto out = trial % 5 == 0 ? mueller::BasisRotation{} : mueller::BasisRotation::ofAngle(4 * u(rng));
        MuellerSpectrum dense = M;
        dense(0, 0) = M(0, 0);  // a write access: dense is no longer marked, rotateBases takes the dense form
        ASSERT_FALSE(dense.interfaceLayout());
        const MuellerSpectrum fast = mueller::rotateBases(M, in, out), want = mueller::rotateBases(dense, in, out);
        const MuellerSpectrum direct = mueller::rotatedInterface(M, in, out), reference = mueller::rotateBasesDense(M, in, out);
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j)
                for (int l = 0; l < n; ++l) {
                    ASSERT_EQ(fast(i, j)[l], want(i, j)[l]) << trial << " (" << i << ", " << j << ") lane " << l;
                    ASSERT_EQ(direct(i, j)[l], reference(i, j)[l]) << trial << " (" << i << ", " << j << ") lane " << l;
                }
    }
}

TEST(Mueller, InterfaceLayoutSurvivesScalingAndSumsOnly) {
    const SampledSpectrum a(4, 0.5f), b(4, 0.25f);
    MuellerSpectrum M = mueller::interfaceMueller(a, b, a, b);
    M *= 2.0f;
    M *= a;
    EXPECT_TRUE(M.interfaceLayout());
    M += mueller::interfaceMueller(b, a, b, a);
    EXPECT_TRUE(M.interfaceLayout());
    M += MuellerSpectrum::absorber(a);  // the identity has the layout, but is not marked: the sum is general
    EXPECT_FALSE(M.interfaceLayout());
    EXPECT_FALSE((mueller::interfaceMueller(a, b, a, b) * mueller::interfaceMueller(a, b, a, b)).interfaceLayout());
    MuellerSpectrum W = mueller::interfaceMueller(a, b, a, b);
    W(0, 2) = a;  // breaks the layout
    EXPECT_FALSE(W.interfaceLayout());
}

TEST(Mueller, DepolarizerProductsStayDepolarizing) {
    const MuellerSpectrum a = MuellerSpectrum::depolarizer(SampledSpectrum(4, 0.5f));
    const MuellerSpectrum b = MuellerSpectrum::depolarizer(SampledSpectrum(4, 0.25f));
    const MuellerSpectrum ab = a * b;
    EXPECT_TRUE(ab.depolarizing());
    EXPECT_FLOAT_EQ(ab(0, 0)[2], 0.125f);
    // With a polarizing matrix the product is general, and only its first row survives.
    const MuellerSpectrum p = mueller::linearPolarizer().spectrum(4);
    const MuellerSpectrum ap = (a * p).expanded();
    EXPECT_FALSE((a * p).depolarizing());
    EXPECT_FLOAT_EQ(ap(0, 1)[0], 0.25f);
    EXPECT_FLOAT_EQ(ap(1, 0)[0], 0.0f);
}

// A depolarizer added to a general matrix (operator+=, which adds only its (0, 0) entry) equals the
// sum of the two dense matrices; a sum into another entry is told apart.
TEST(Mueller, SumWithADepolarizerEqualsTheDenseSum) {
    std::mt19937 rng(6);
    std::uniform_real_distribution<float> u(-1, 1);
    for (int n : {1, 4, 7}) {
        auto random = [&] { return SampledSpectrum::fromLanes(n, [&](int) { return u(rng); }); };
        const MuellerSpectrum M = mueller::interfaceMueller(random(), random(), random(), random());
        const MuellerSpectrum d = MuellerSpectrum::depolarizer(random());
        MuellerSpectrum sum = M;
        sum += d;
        EXPECT_FALSE(sum.interfaceLayout());
        const MuellerSpectrum dense = d.expanded();
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j)
                for (int l = 0; l < n; ++l) {
                    EXPECT_EQ(sum(i, j)[l], M(i, j)[l] + dense(i, j)[l]) << i << j;
                    if (i == 1 && j == 1) EXPECT_NE(sum(i, j)[l], M(i, j)[l] + dense(0, 0)[l]);
                }
    }
}
