// spectral/thin_film_industry: KHR_materials_iridescence's RGB thin film as its README writes it,
// Gulbrandsen 2014's metal index, and the exact film reflectance they are measured against.
#include <cmath>

#include <gtest/gtest.h>

#include "spectral/thin_film_industry.h"

namespace iris {
namespace {

/// The README's incoherent limit: for OPD → ∞ the Gaussian envelope exp(−phase² var) removes the
/// harmonics, leaving C0 = R12 + T121² R23 / (1 − R12 R23) (Belcour & Barla 2017, the m = 0 term).
double khrDcTerm(double outside, double film, double baseF0, double cos1) {
    const double sin2 = std::pow(outside / film, 2) * (1 - cos1 * cos1);
    const double cos2 = std::sqrt(1 - sin2);
    const double R12 = schlickFresnel(iorToFresnel0(film, outside), cos1);
    const double baseIor = fresnel0ToIor(baseF0 + 0.0001);
    const double R23 = schlickFresnel(iorToFresnel0(baseIor, film), cos2);
    const double R123 = std::clamp(R12 * R23, 1e-5, 0.9999);
    return R12 + (1 - R12) * (1 - R12) * R23 / (1 - R123);
}

TEST(ThinFilmIndustry, SchlickAndIorConversionsAreInverse) {
    EXPECT_DOUBLE_EQ(schlickFresnel(0.04, 1.0), 0.04);
    EXPECT_DOUBLE_EQ(schlickFresnel(0.04, 0.0), 1.0);
    EXPECT_NEAR(iorToFresnel0(1.5, 1.0), 0.04, 1e-15);
    for (double n : {1.2, 1.5, 2.3, 3.0}) EXPECT_NEAR(fresnel0ToIor(iorToFresnel0(n, 1.0)), n, 1e-12) << n;
}

TEST(ThinFilmIndustry, KhrThickFilmReducesToTheIncoherentTerm) {
    // 100 µm: phase² var ≈ 4e8 for every lobe, so the harmonics are exp(−4e8) = 0.
    for (double cos1 : {1.0, 0.7, 0.3})
        for (double f0 : {0.04, 0.5, 0.9}) {
            const dvec3 F = khrIridescentFresnel(1.0, 1.8, dvec3(f0), 1e5, cos1);
            for (int c = 0; c < 3; ++c) EXPECT_NEAR(F[c], khrDcTerm(1.0, 1.8, f0, cos1), 1e-12) << cos1 << " " << f0;
        }
}

TEST(ThinFilmIndustry, KhrIsFiniteForAPerfectMirrorBase) {
    // The README's guard F0 + 0.0001 divides by zero at F0 = 0.9999; iris caps it (a documented addition).
    for (double f0 : {0.9999, 1.0})
        for (double d : {0.0, 300.0}) {
            const dvec3 F = khrIridescentFresnel(1.0, 1.5, dvec3(f0), d, 0.7);
            for (int c = 0; c < 3; ++c) EXPECT_TRUE(std::isfinite(F[c])) << f0 << " " << d;
        }
}

TEST(ThinFilmIndustry, KhrTotalInternalReflectionIsOne) {
    // A film less dense than the outside medium reflects totally beyond its critical angle.
    const dvec3 F = khrIridescentFresnel(1.5, 1.2, dvec3(0.04), 300, 0.3);
    EXPECT_EQ(F, dvec3(1.0));
    const dvec3 inside = khrIridescentFresnel(1.5, 1.2, dvec3(0.04), 300, 0.9);
    EXPECT_LT(inside.x, 1.0);
}

TEST(ThinFilmIndustry, KhrSensitivityMatchesTheReadmeAtZeroPath) {
    // S(0, 0): the Gaussians' areas val·sqrt(2π var) / 1.0685e−7 in XYZ, then XYZ_TO_REC709.
    const double x = (5.4856e-13 * std::sqrt(2 * M_PI * 4.3278e+09) + 9.7470e-14 * std::sqrt(2 * M_PI * 4.5282e+09)) / 1.0685e-7;
    const double y = 4.4201e-13 * std::sqrt(2 * M_PI * 9.3046e+09) / 1.0685e-7;
    const double z = 5.2481e-13 * std::sqrt(2 * M_PI * 6.6121e+09) / 1.0685e-7;
    const dvec3 s = khrSensitivity(0.0, dvec3(0.0));
    EXPECT_NEAR(s.x, 3.2404542 * x - 1.5371385 * y - 0.4985314 * z, 1e-12);
    EXPECT_NEAR(s.y, -0.9692660 * x + 1.8760108 * y + 0.0415560 * z, 1e-12);
    EXPECT_NEAR(s.z, 0.0556434 * x - 0.2040259 * y + 1.0572252 * z, 1e-12);
    // A phase shift of π negates every lobe.
    const dvec3 shifted = khrSensitivity(0.0, dvec3(M_PI));
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(shifted[c], -s[c], 1e-12);
}

TEST(ThinFilmIndustry, GulbrandsenReproducesTheNormalReflectivity) {
    for (double r : {0.05, 0.3, 0.6, 0.95})
        for (double g : {0.0, 0.5, 1.0}) {
            const complexd n = gulbrandsenIor(r, g);
            const double R = (std::pow(n.real() - 1, 2) + n.imag() * n.imag()) / (std::pow(n.real() + 1, 2) + n.imag() * n.imag());
            EXPECT_NEAR(R, r, 1e-12) << r << " " << g;
            EXPECT_GE(n.imag(), 0.0);
        }
    // g = 0: a dielectric-like index, n = n_max = (1 + √r)/(1 − √r), k = 0; g = 1: n = n_min =
    // (1 − r)/(1 + r) with k = 2√r/(1 + r) (substituting n_min into k²).
    const double sr = std::sqrt(0.3);
    EXPECT_NEAR(gulbrandsenIor(0.3, 0.0).real(), (1 + sr) / (1 - sr), 1e-12);
    EXPECT_NEAR(gulbrandsenIor(0.3, 0.0).imag(), 0.0, 1e-6);
    EXPECT_NEAR(gulbrandsenIor(0.3, 1.0).real(), 0.7 / 1.3, 1e-12);
    EXPECT_NEAR(gulbrandsenIor(0.3, 1.0).imag(), 2 * sr / 1.3, 1e-12);
}

TEST(ThinFilmIndustry, ExactFilmOfZeroThicknessIsTheBareSubstrate) {
    const complexd gold(0.47, 2.4);
    for (double c : {1.0, 0.6, 0.2}) {
        const double bare = fresnelInterfaceRT(c, 1.0, gold).R();
        EXPECT_NEAR(exactThinFilmReflectance(550, c, 1.0, 1.8, 0.0, gold), bare, 1e-12);
        EXPECT_GT(std::abs(exactThinFilmReflectance(550, c, 1.0, 1.8, 120.0, gold) - bare), 1e-3) << "a film must change it";
    }
}

}  // namespace
}  // namespace iris
