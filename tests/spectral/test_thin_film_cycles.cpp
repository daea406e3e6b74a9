// spectral/thin_film_cycles: Blender Cycles 4.2's thin film against its limiting cases, where the
// approximation must agree with the exact film (spectral/thin_film_industry.h), and against the
// quantities its source publishes (the 30 nm blend, three harmonics, the white point).
#include <cmath>

#include <gtest/gtest.h>

#include "spectral/cie.h"
#include "spectral/thin_film_cycles.h"
#include "spectral/thin_film_industry.h"
#include "spectral/thin_film_stack.h"

namespace iris {
namespace {

/// The textbook unpolarised Fresnel reflectance between real indices (outside n1, base n3).
double bareFresnel(double n1, double n3, double cos1) { return fresnelInterfaceRT(cos1, n1, complexd(n3, 0.0)).R(); }

TEST(ThinFilmCycles, SmoothstepAndThe30nmBlendOfTheFilmIndex) {
    EXPECT_EQ(cyclesSmoothstep(0, 30, -1), 0.0);
    EXPECT_EQ(cyclesSmoothstep(0, 30, 30), 1.0);
    EXPECT_DOUBLE_EQ(cyclesSmoothstep(0, 30, 15), 0.5);
    EXPECT_DOUBLE_EQ(cyclesSmoothstep(0, 30, 7.5), 3 * 0.0625 - 2 * 0.015625);  // 3t² − 2t³, t = 1/4
    EXPECT_DOUBLE_EQ(cyclesFilmIndex(1.0, 2.0, 0.0), 1.0);
    EXPECT_DOUBLE_EQ(cyclesFilmIndex(1.0, 2.0, 15.0), 1.5);
    EXPECT_DOUBLE_EQ(cyclesFilmIndex(1.0, 2.0, 30.0), 2.0);
    EXPECT_DOUBLE_EQ(cyclesFilmIndex(1.0, 2.0, 500.0), 2.0);
}

TEST(ThinFilmCycles, BelowTheCutoffItIsTheExactBareBase) {
    // d ≤ 0.1 nm: the Principled BSDF's plain dielectric Fresnel, which the exact film of zero
    // thickness also is.
    for (double d : {0.0, 0.05, 0.1})
        for (double c : {1.0, 0.7, 0.3, 0.05}) {
            const dvec3 F = cyclesThinFilmRGB(1.0, 1.8, 1.5, c, d);
            const double exact = exactThinFilmReflectance(550.0, c, 1.0, 1.8, 0.0, complexd(1.5, 0.0));
            for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(F[ch], exact, 1e-12) << d << " " << c;
        }
}

TEST(ThinFilmCycles, The30nmBlendMakesAThinFilmOfTheBaseIndexInvisible) {
    // At 15 nm the film index is mix(1, 2, 0.5) = 1.5, the base's: no interface at the bottom, so
    // the reading is the bare base's Fresnel in every channel. Without the blend (a 2.0 film,
    // which is what exact optics sees) it is not.
    for (double c : {1.0, 0.6, 0.2}) {
        const dvec3 F = cyclesThinFilmRGB(1.0, 2.0, 1.5, c, 15.0);
        for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(F[ch], bareFresnel(1.0, 1.5, c), 1e-9) << c;
        EXPECT_GT(std::abs(exactThinFilmReflectance(550.0, c, 1.0, 2.0, 15.0, complexd(1.5, 0.0)) - bareFresnel(1.0, 1.5, c)), 1e-3);
    }
}

TEST(ThinFilmCycles, FilmsWithoutAnInterfaceMatchTheExactReading) {
    // A film of the outside's index (no top interface) or of the base's (no bottom interface) has
    // no interference: every harmonic has C_m = 0 and the reading is exact.
    for (double c : {1.0, 0.5, 0.15})
        for (double d : {80.0, 420.0, 1300.0}) {
            const dvec3 sameAsOutside = cyclesThinFilmRGB(1.0, 1.0, 1.6, c, d);
            const dvec3 sameAsBase = cyclesThinFilmRGB(1.0, 1.6, 1.6, c, d);
            for (double lambda : {450.0, 550.0, 650.0})
                for (int ch = 0; ch < 3; ++ch) {
                    EXPECT_NEAR(sameAsOutside[ch], exactThinFilmReflectance(lambda, c, 1.0, 1.0, d, complexd(1.6, 0.0)), 1e-9);
                    EXPECT_NEAR(sameAsBase[ch], exactThinFilmReflectance(lambda, c, 1.0, 1.6, d, complexd(1.6, 0.0)), 1e-9);
                }
        }
}

TEST(ThinFilmCycles, AThickFilmIsTheNeutralIncoherentSum) {
    // 100 µm: every harmonic's Gaussian envelope is exp(−4e8), so the XYZ result is C0·(1, 1, 1)
    // per polarisation; the white-point product then makes it grey, C0 = R12 + T121² R23/(1 − R12 R23).
    const double n1 = 1.0, n2 = 1.45, n3 = 1.7;
    for (double c1 : {1.0, 0.6, 0.25}) {
        const double s1 = std::sqrt(1 - c1 * c1), c2 = std::sqrt(1 - std::pow(n1 * s1 / n2, 2));
        const double c3 = std::sqrt(1 - std::pow(n1 * s1 / n3, 2));
        const double rs12 = (n1 * c1 - n2 * c2) / (n1 * c1 + n2 * c2), rp12 = (n2 * c1 - n1 * c2) / (n2 * c1 + n1 * c2);
        const double rs23 = (n2 * c2 - n3 * c3) / (n2 * c2 + n3 * c3), rp23 = (n3 * c2 - n2 * c3) / (n3 * c2 + n2 * c3);
        double C0 = 0;
        for (auto [r12, r23] : {std::pair{rs12, rs23}, std::pair{rp12, rp23}}) {
            const double R12 = r12 * r12, R23 = r23 * r23, T = 1 - R12;
            C0 += 0.5 * (R12 + T * T * R23 / (1 - R12 * R23));
        }
        const dvec3 F = cyclesThinFilmRGB(n1, n2, n3, c1, 1e5);
        for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(F[ch], C0, 1e-9) << c1;
    }
    // The white is the XYZ of Rec.709 white, D65 with Y = 1.
    EXPECT_NEAR(cyclesRec709WhiteXYZ().x, 0.95047, 1e-4);
    EXPECT_NEAR(cyclesRec709WhiteXYZ().y, 1.0, 1e-6);
    EXPECT_NEAR(cyclesRec709WhiteXYZ().z, 1.08883, 1e-4);
}

TEST(ThinFilmCycles, TheAirySumStopsAfterThreeHarmonics) {
    // At OPD = 0 and φ = 0 every sensitivity is S(0, 0): R = C0 + 2 S0 Σ_{m=1..3} (Rs − T121) r123^m.
    const double R12 = 0.2, R23 = 0.5, T = 1 - R12, r = std::sqrt(R12 * R23), Rs = T * T * R23 / (1 - R12 * R23);
    const dvec3 S0 = cyclesSensitivityXYZ(0.0, 0.0);
    const dvec3 R = cyclesAirySummationXYZ(T, R12, R23, 0.0, 0.0);
    for (int ch = 0; ch < 3; ++ch) {
        const double three = R12 + Rs + 2 * S0[ch] * (Rs - T) * (r + r * r + r * r * r);
        EXPECT_NEAR(R[ch], three, 1e-12);
        EXPECT_GT(std::abs(R[ch] - (three + 2 * S0[ch] * (Rs - T) * std::pow(r, 4))), 1e-4) << "a fourth harmonic would show";
    }
    // The fit's zero-path sensitivity is close to 1 in X, Y and Z (its published normalisation).
    for (int ch = 0; ch < 3; ++ch) EXPECT_NEAR(S0[ch], 1.0, 2e-3);
}

/// What the reading approximates: the exact Airy reflectance integrated against the CIE 1931
/// functions (1 nm, normalised by ∫ȳ, so a flat spectrum is X = Y = Z = 1, the fit's normalisation),
/// times the Rec.709 white's XYZ, in Rec.709, clamped (spectral/thin_film_cycles.h).
dvec3 integratedAiryRGB(double n2, double n3, double cos1, double d) {
    dvec3 xyz(0.0);
    for (int l = cie::kQuadratureFirst; l <= cie::kQuadratureLast; ++l)
        xyz += dvec3(cie::xyzBar(float(l))) * exactThinFilmReflectance(l, cos1, 1.0, n2, d, complexd(n3, 0.0));
    return glm::clamp(cyclesXyzToRec709(xyz / cie::yIntegral() * cyclesRec709WhiteXYZ()), dvec3(0.0), dvec3(1.0));
}

TEST(ThinFilmCycles, ApproximatesTheSpectralIntegralOfTheExactFilm) {
    // The Gaussian fit and the three harmonics are approximations, but the phases and the colour
    // conversion must be right: a sign error in φ or a missing white product is off by ~0.1.
    double maxErr = 0, sumErr = 0;
    int count = 0;
    for (double n2 : {1.3, 1.8, 2.3})
        for (double n3 : {1.5, 1.2})
            for (double c : {1.0, 0.5})
                for (double d : {50.0, 150.0, 290.0, 600.0, 1200.0}) {
                    const dvec3 F = cyclesThinFilmRGB(1.0, n2, n3, c, d), ref = integratedAiryRGB(n2, n3, c, d);
                    for (int ch = 0; ch < 3; ++ch) {
                        maxErr = std::max(maxErr, std::abs(F[ch] - ref[ch]));
                        sumErr += std::abs(F[ch] - ref[ch]);
                        ++count;
                    }
                }
    EXPECT_LT(maxErr, 0.03) << "mean " << sumErr / count;
    EXPECT_LT(sumErr / count, 0.005);
    std::printf("Cycles 4.2 against the integrated exact film: max %.4f, mean %.5f over %d values\n", maxErr, sumErr / count, count);
}

TEST(ThinFilmCycles, TotalReflectionAndRange) {
    // A film less dense than the outside reflects totally beyond its critical angle.
    EXPECT_EQ(cyclesThinFilmRGB(1.5, 1.2, 1.5, 0.3, 300.0), dvec3(1.0));
    for (double d = 31.0; d < 1500.0; d += 37.0)
        for (double c : {1.0, 0.5, 0.1}) {
            const dvec3 F = cyclesThinFilmRGB(1.0, 2.3, 1.5, c, d);
            for (int ch = 0; ch < 3; ++ch) {
                EXPECT_GE(F[ch], 0.0);
                EXPECT_LE(F[ch], 1.0);
            }
        }
}

}  // namespace
}  // namespace iris
