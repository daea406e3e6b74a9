// A film stack's Mueller matrices (spectral/thin_film_polarization.h, thin_film_mueller.h) against
// physics: the entries are |r_s|², |r_p|², Re and Im of r_s r_p* of an independent transfer matrix
// to 1e-12; the response to unpolarized light is today's unpolarized R and T; coherent stacks are
// pure (C² + D² = R_s R_p), incoherent sums depolarize.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "spectral/thin_film_airy.h"
#include "spectral/thin_film_mueller.h"

using namespace iris;

namespace {

/// Born & Wolf §1.6.2 characteristic matrices for e^{−iωt} (Macleod ch. 2 with i → −i), without any
/// scaling — fine for the moderate thicknesses and absorptions used here: r = (y0 B − C)/(y0 B + C),
/// t = 2 y0 / (y0 B + C), T = Re(y_sub)/y0 |t|² (tangential fields; y_s = n cos θ, y_p = n / cos θ
/// written as q/ñ² with q = ñ cos θ for p, the tangential-H form of thin_film_stack.h).
struct Naive {
    complexd r[2], t[2];
    double T[2];
};
Naive naiveStack(double lambda, double cosI, double n0, const std::vector<Layer>& layers, complexd sub) {
    const double s = n0 * std::sqrt(1 - cosI * cosI);
    auto q = [&](complexd n) {
        complexd v = std::sqrt(n * n - s * s);
        return v.imag() < 0 || (v.imag() == 0 && v.real() < 0) ? -v : v;
    };
    Naive out{};
    for (int pol = 0; pol < 2; ++pol) {
        auto y = [&](complexd n) { return pol == 0 ? q(n) : q(n) / (n * n); };
        const complexd y0 = y(n0), ys = y(sub);
        complexd m00 = 1, m01 = 0, m10 = 0, m11 = 1;
        for (const Layer& l : layers) {
            const complexd d = 2 * 3.14159265358979323846 / lambda * l.thicknessNm * q(l.ior);
            const complexd yl = y(l.ior), c = std::cos(d), sn = std::sin(d);
            const complexd a00 = c, a01 = complexd(0, -1) * sn / yl, a10 = complexd(0, -1) * yl * sn, a11 = c;
            const complexd n00 = m00 * a00 + m01 * a10, n01 = m00 * a01 + m01 * a11;
            const complexd n10 = m10 * a00 + m11 * a10, n11 = m10 * a01 + m11 * a11;
            m00 = n00, m01 = n01, m10 = n10, m11 = n11;
        }
        const complexd B = m00 + m01 * ys, C = m10 + m11 * ys;
        out.r[pol] = (y0 * B - C) / (y0 * B + C);
        out.t[pol] = 2.0 * y0 / (y0 * B + C);
        out.T[pol] = ys.real() / y0.real() * std::norm(out.t[pol]);
    }
    return out;
}

std::vector<Layer> randomStack(std::mt19937& rng, int n) {
    std::uniform_real_distribution<double> u(0, 1);
    std::vector<Layer> l;
    for (int i = 0; i < n; ++i) l.push_back({complexd(1.1 + 1.5 * u(rng), u(rng) < 0.5 ? 0.0 : 0.3 * u(rng)), 600 * u(rng)});
    return l;
}

}  // namespace

TEST(FilmMueller, EntriesAreTheTransferMatrixAmplitudes) {
    std::mt19937 rng(21);
    std::uniform_real_distribution<double> u(0, 1);
    double worst = 0;
    for (int i = 0; i < 3000; ++i) {
        const std::vector<Layer> layers = randomStack(rng, 1 + i % 4);
        const complexd sub = u(rng) < 0.5 ? complexd(1.2 + u(rng), 0) : complexd(0.2 + u(rng), 2 + 3 * u(rng));
        const double cosI = 0.05 + 0.95 * u(rng), n0 = 1 + 0.5 * u(rng), lambda = 380 + 400 * u(rng);
        const Naive ref = naiveStack(lambda, cosI, n0, layers, sub);
        const Mueller4d R = reflectionMueller(stackPolarization(lambda, cosI, n0, layers, sub));
        const double Rs = std::norm(ref.r[0]), Rp = std::norm(ref.r[1]);
        const complexd x = ref.r[0] * std::conj(ref.r[1]);
        const double want[4][4] = {{(Rs + Rp) / 2, (Rs - Rp) / 2, 0, 0}, {(Rs - Rp) / 2, (Rs + Rp) / 2, 0, 0},
                                   {0, 0, x.real(), -x.imag()}, {0, 0, x.imag(), x.real()}};
        for (int a = 0; a < 4; ++a)
            for (int b = 0; b < 4; ++b) {
                EXPECT_NEAR(R.m[a][b], want[a][b], 1e-12) << i << " (" << a << ", " << b << ")";
                worst = std::max(worst, std::abs(R.m[a][b] - want[a][b]));
            }
        if (sub.imag() != 0) continue;  // transmission into a real substrate
        const Mueller4d T = transmissionMueller(stackPolarization(lambda, cosI, n0, layers, sub));
        const complexd xt = ref.t[0] * std::conj(ref.t[1]);
        const complexd cross = std::abs(xt) > 0 ? std::sqrt(ref.T[0] * ref.T[1]) * xt / std::abs(xt) : 0.0;
        EXPECT_NEAR(T.m[0][0], (ref.T[0] + ref.T[1]) / 2, 1e-12);
        EXPECT_NEAR(T.m[0][1], (ref.T[0] - ref.T[1]) / 2, 1e-12);
        EXPECT_NEAR(T.m[2][2], cross.real(), 1e-12);
        EXPECT_NEAR(T.m[3][2], cross.imag(), 1e-12);
    }
    RecordProperty("max_abs_difference", std::to_string(worst));
}

// The closed form the materials use for an exact single film (airySingleFilmPolarizationAt) against
// the transfer matrix (stackPolarization) and the naive characteristic matrix: absorbing films,
// conductor substrates, and light from a denser medium (total internal reflection).
TEST(FilmMueller, ExactSingleFilmClosedFormIsTheTransferMatrix) {
    std::mt19937 rng(24);
    std::uniform_real_distribution<double> u(0, 1);
    int fast = 0;
    for (int i = 0; i < 4000; ++i) {
        const Layer film{complexd(1.05 + 2 * u(rng), u(rng) < 0.5 ? 0.0 : 0.3 * u(rng)), 1500 * u(rng)};
        const complexd sub = u(rng) < 0.5 ? complexd(1.0 + u(rng), 0) : complexd(0.1 + u(rng), 4 * u(rng));
        const double cosI = 0.02 + 0.98 * u(rng), n0 = 1 + u(rng), lambda = 360 + 470 * u(rng);
        FilmPolarization p;
        if (!airySingleFilmPolarizationAt(airyAngle(cosI, n0), airyFilmConstants(lambda, film), squaredIndex(sub), p)) continue;
        ++fast;
        ThinFilmStackResult airy;  // the powers are the spectral kernel's, bit for bit
        ASSERT_TRUE(airySingleFilmFast(cosI, n0, airyFilmConstants(lambda, film), squaredIndex(sub), airy));
        EXPECT_EQ(p.power.Rs, airy.Rs);
        EXPECT_EQ(p.power.Rp, airy.Rp);
        EXPECT_EQ(p.power.Ts, airy.Ts);
        EXPECT_EQ(p.power.Tp, airy.Tp);
        const FilmPolarization tmm = stackPolarization(lambda, cosI, n0, std::span<const Layer>(&film, 1), sub);
        EXPECT_NEAR(p.crossR.real(), tmm.crossR.real(), 1e-12) << i;
        EXPECT_NEAR(p.crossR.imag(), tmm.crossR.imag(), 1e-12) << i;
        EXPECT_NEAR(p.crossT.real(), tmm.crossT.real(), 1e-12) << i;
        EXPECT_NEAR(p.crossT.imag(), tmm.crossT.imag(), 1e-12) << i;
        const Naive ref = naiveStack(lambda, cosI, n0, {film}, sub);
        const complexd x = ref.r[0] * std::conj(ref.r[1]);
        EXPECT_NEAR(p.crossR.real(), x.real(), 1e-12) << i;
        EXPECT_NEAR(p.crossR.imag(), x.imag(), 1e-12) << i;
        if (sub.imag() != 0) continue;  // transmission into a real substrate
        const complexd xt = ref.t[0] * std::conj(ref.t[1]);
        const complexd cross = std::abs(xt) > 0 ? std::sqrt(ref.T[0] * ref.T[1]) * xt / std::abs(xt) : 0.0;
        EXPECT_NEAR(p.crossT.real(), cross.real(), 1e-12) << i;
        EXPECT_NEAR(p.crossT.imag(), cross.imag(), 1e-12) << i;
    }
    EXPECT_GT(fast, 3900);  // the closed form declines only at q1 = 0 exactly
}

TEST(FilmMueller, UnpolarizedResponseIsTodaysReflectanceAndTransmittance) {
    std::mt19937 rng(22);
    std::uniform_real_distribution<double> u(0, 1);
    for (int i = 0; i < 3000; ++i) {
        const Layer film{complexd(1.05 + 2 * u(rng), u(rng) < 0.5 ? 0.0 : 0.5 * u(rng)), 2000 * u(rng)};
        const complexd sub = u(rng) < 0.5 ? complexd(1.0 + u(rng), 0) : complexd(0.1 + u(rng), 4 * u(rng));
        const double cosI = u(rng), n0 = 1 + u(rng), lambda = 360 + 470 * u(rng);
        // Exact: the fast Airy sum the materials use.
        const ThinFilmStackResult airy = airySingleFilm(lambda, cosI, n0, film, sub);
        const FilmPolarization p = singleFilmPolarization(ThinFilmPhaseMode::Exact, 1, lambda, cosI, n0, film, sub);
        EXPECT_NEAR(reflectionMueller(p).m[0][0], airy.R(), 1e-12) << i;
        EXPECT_NEAR(transmissionMueller(p).m[0][0], airy.T(), 1e-12) << i;
        // Incoherent: the same sums (bit for bit: the same operations).
        const ThinFilmStackResult inc = incoherentSingleFilm(lambda, cosI, n0, film, sub);
        const FilmPolarization pi = singleFilmPolarization(ThinFilmPhaseMode::Incoherent, 1, lambda, cosI, n0, film, sub);
        EXPECT_EQ(reflectionMueller(pi).m[0][0], inc.R());
        EXPECT_EQ(transmissionMueller(pi).m[0][0], inc.T());
        // Truncated: the sums the materials clamp (R ≤ 1, T ≤ 1 − R per polarization).
        const int K = 1 + i % 4;
        ThinFilmStackResult tr = truncatedSingleFilm(lambda, cosI, n0, film, sub, K);
        tr.Rs = std::clamp(tr.Rs, 0.0, 1.0), tr.Rp = std::clamp(tr.Rp, 0.0, 1.0);
        tr.Ts = std::clamp(tr.Ts, 0.0, 1.0 - tr.Rs), tr.Tp = std::clamp(tr.Tp, 0.0, 1.0 - tr.Rp);
        const FilmPolarization pt = singleFilmPolarization(ThinFilmPhaseMode::Truncated, K, lambda, cosI, n0, film, sub);
        EXPECT_NEAR(reflectionMueller(pt).m[0][0], tr.R(), 1e-12) << i;
        EXPECT_NEAR(transmissionMueller(pt).m[0][0], tr.T(), 1e-12) << i;
    }
    // Stacks of several layers: the transfer matrix's R and T.
    for (int i = 0; i < 500; ++i) {
        const std::vector<Layer> layers = randomStack(rng, 2 + i % 5);
        const complexd sub(1.0 + u(rng), 0);
        const double cosI = u(rng), lambda = 360 + 470 * u(rng);
        const ThinFilmStackResult tmm = thinFilmStackRT(lambda, cosI, 1.0, layers, sub);
        const FilmPolarization p = stackPolarization(lambda, cosI, 1.0, layers, sub);
        EXPECT_EQ(reflectionMueller(p).m[0][0], tmm.R());
        EXPECT_EQ(transmissionMueller(p).m[0][0], tmm.T());
    }
}

TEST(FilmMueller, CoherentStacksArePureAndIncoherentOnesDepolarize) {
    std::mt19937 rng(23);
    std::uniform_real_distribution<double> u(0, 1);
    double minRatio = 1;
    for (int i = 0; i < 2000; ++i) {
        const Layer film{complexd(1.2 + u(rng), 0.0), 100 + 900 * u(rng)};
        const complexd sub(1.5 + u(rng), 0);
        const double cosI = 0.2 + 0.8 * u(rng), lambda = 400 + 300 * u(rng);
        const FilmPolarization p = singleFilmPolarization(ThinFilmPhaseMode::Exact, 1, lambda, cosI, 1.0, film, sub);
        EXPECT_NEAR(std::norm(p.crossR), p.power.Rs * p.power.Rp, 1e-12);  // a pure (non-depolarizing) matrix
        const FilmPolarization q = singleFilmPolarization(ThinFilmPhaseMode::Incoherent, 1, lambda, cosI, 1.0, film, sub);
        EXPECT_LE(std::norm(q.crossR), q.power.Rs * q.power.Rp * (1 + 1e-12));
        minRatio = std::min(minRatio, std::norm(q.crossR) / (q.power.Rs * q.power.Rp));
    }
    EXPECT_LT(minRatio, 0.9);  // the beams of the incoherent sum add partially polarized light
}
