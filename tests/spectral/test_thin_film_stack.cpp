// Thin-film stack optics (spectral/thin_film_stack.h) checked against physics: bare Fresnel limits,
// absentee and quarter-wave layers, energy conservation, TMM == Airy, incoherent limits,
// truncation convergence and robustness over a dense parameter grid.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "spectral/thin_film_stack.h"

namespace iris {
namespace {

constexpr double kPiD = 3.14159265358979323846;

// Independent reference: unpolarised-split conductor Fresnel reflectance with the real-arithmetic
// formulas of Born & Wolf ch. 14 (as written in e.g. pbrt-v3 §8.2.1), relative index η + ik = ñ_t/n_i.
void bareFresnel(double cosI, double ni, complexd nt, double& Rs, double& Rp) {
    const double eta = nt.real() / ni, k = nt.imag() / ni;
    const double c2 = cosI * cosI, s2 = 1 - c2;
    const double t0 = eta * eta - k * k - s2;
    const double a2b2 = std::sqrt(t0 * t0 + 4 * eta * eta * k * k);
    const double a = std::sqrt(std::max(0.0, 0.5 * (a2b2 + t0)));
    const double t1 = a2b2 + c2, t2 = 2 * cosI * a;
    Rs = (t1 - t2) / (t1 + t2);
    const double t3 = c2 * a2b2 + s2 * s2, t4 = t2 * s2;
    Rp = Rs * (t3 - t4) / (t3 + t4);
}

TEST(FilmStack, ZeroThicknessGivesBareFresnel) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(0, 1);
    for (int i = 0; i < 2000; ++i) {
        const double n0 = 1.0 + u(rng);
        const complexd sub(0.2 + 3.5 * u(rng), u(rng) < 0.5 ? 0.0 : 8 * u(rng));
        const double cosI = u(rng);
        const Layer film{complexd(1 + 2 * u(rng), 3 * u(rng) * (u(rng) < 0.5)), 0.0};
        const double lambda = 360 + 470 * u(rng);
        double Rs, Rp;
        bareFresnel(cosI, n0, sub, Rs, Rp);
        const ThinFilmStackResult tmm = thinFilmStackRT(lambda, cosI, n0, std::span(&film, 1), sub);
        const ThinFilmStackResult airy = airySingleFilm(lambda, cosI, n0, film, sub);
        const ThinFilmStackResult bare = fresnelInterfaceRT(cosI, n0, sub);
        const FresnelAmplitudes amp = fresnelAmplitudes(cosI, n0, sub);
        EXPECT_NEAR(tmm.Rs, Rs, 1e-12);
        EXPECT_NEAR(tmm.Rp, Rp, 1e-12);
        EXPECT_NEAR(airy.Rs, Rs, 1e-12);
        EXPECT_NEAR(airy.Rp, Rp, 1e-12);
        EXPECT_NEAR(bare.Rs, Rs, 1e-12);
        EXPECT_NEAR(bare.Rp, Rp, 1e-12);
        EXPECT_NEAR(std::norm(amp.rs), Rs, 1e-12);
        EXPECT_NEAR(std::norm(amp.rp), Rp, 1e-12);
        EXPECT_NEAR(tmm.Ts, airy.Ts, 1e-12);
        EXPECT_NEAR(tmm.Tp, airy.Tp, 1e-12);
        if (sub.imag() == 0 && n0 * std::sqrt(1 - cosI * cosI) < sub.real() - 1e-6) {
            EXPECT_NEAR(tmm.Rs + tmm.Ts, 1.0, 1e-12);
            EXPECT_NEAR(tmm.Rp + tmm.Tp, 1.0, 1e-12);
            // Field transmission amplitudes: T = Re(n_t cosθ_t)/(n_i cosθ_i) |t|² (Born & Wolf §1.5.3).
            const double s = n0 * std::sqrt(1 - cosI * cosI);
            const double qt = std::sqrt(sub.real() * sub.real() - s * s);
            if (cosI > 1e-3) {
                EXPECT_NEAR(qt / (n0 * cosI) * std::norm(amp.ts), tmm.Ts, 1e-10);
                EXPECT_NEAR(qt / (n0 * cosI) * std::norm(amp.tp), tmm.Tp, 1e-10);  // same form for p
            }
        }
    }
}

TEST(FilmStack, HalfWaveLayerIsAbsentee) {
    const double n0 = 1.0, n1 = 2.1;
    const complexd sub(1.52, 0.0), metal(0.18, 3.4);
    for (double lambda : {400.0, 550.0, 700.0}) {
        for (complexd s : {sub, metal}) {
            // Normal incidence: d = λ/(2 n1).
            const Layer film{complexd(n1, 0), lambda / (2 * n1)};
            const ThinFilmStackResult bare = fresnelInterfaceRT(1.0, n0, s);
            const ThinFilmStackResult tmm = thinFilmStackRT(lambda, 1.0, n0, std::span(&film, 1), s);
            const ThinFilmStackResult airy = airySingleFilm(lambda, 1.0, n0, film, s);
            EXPECT_NEAR(tmm.R(), bare.R(), 1e-12);
            EXPECT_NEAR(airy.R(), bare.R(), 1e-12);
            EXPECT_NEAR(tmm.T(), bare.T(), 1e-12);
            // 45°: the design thickness uses the layer's own cosθ1: d = λ/(2 n1 cosθ1).
            const double c = std::sqrt(0.5), sinv = n0 * std::sqrt(0.5);
            const double q1 = std::sqrt(n1 * n1 - sinv * sinv);
            const Layer film45{complexd(n1, 0), lambda / (2 * q1)};
            const ThinFilmStackResult bare45 = fresnelInterfaceRT(c, n0, s);
            const ThinFilmStackResult tmm45 = thinFilmStackRT(lambda, c, n0, std::span(&film45, 1), s);
            EXPECT_NEAR(tmm45.Rs, bare45.Rs, 1e-12);
            EXPECT_NEAR(tmm45.Rp, bare45.Rp, 1e-12);
            EXPECT_NEAR(tmm45.Ts, bare45.Ts, 1e-12);
            EXPECT_NEAR(tmm45.Tp, bare45.Tp, 1e-12);
            // Off-design (at another wavelength) the layer is not absent.
            const ThinFilmStackResult off = thinFilmStackRT(lambda * 1.3, c, n0, std::span(&film45, 1), s);
            EXPECT_GT(std::abs(off.R() - fresnelInterfaceRT(c, n0, s).R()), 1e-3);
        }
    }
}

TEST(FilmStack, QuarterWaveCoating) {
    // Macleod, antireflection-coatings chapter: R = ((n0 ns − n1²)/(n0 ns + n1²))² at the design wavelength, normal incidence.
    for (double n1 : {1.22, 1.38, 1.7, 2.35}) {
        for (double ns : {1.45, 1.52, 1.8}) {
            const double lambda = 550, n0 = 1.0;
            const Layer film{complexd(n1, 0), lambda / (4 * n1)};
            const double expected = std::pow((n0 * ns - n1 * n1) / (n0 * ns + n1 * n1), 2);
            EXPECT_NEAR(thinFilmStackRT(lambda, 1.0, n0, std::span(&film, 1), complexd(ns, 0)).R(), expected, 1e-12);
            EXPECT_NEAR(airySingleFilm(lambda, 1.0, n0, film, complexd(ns, 0)).R(), expected, 1e-12);
        }
    }
}

TEST(FilmStack, LosslessStacksConserveEnergyAtAllAngles) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(0, 1);
    int beyondCritical = 0;
    for (int i = 0; i < 3000; ++i) {
        const double n0 = 1.0 + 1.5 * u(rng);  // often denser than the substrate
        const complexd sub(1.0 + 1.5 * u(rng), 0);
        const int nl = 1 + int(u(rng) * 6);
        std::vector<Layer> layers;
        for (int j = 0; j < nl; ++j) layers.push_back({complexd(1.0 + 2.5 * u(rng), 0), 2000 * u(rng)});
        const double cosI = i % 10 == 0 ? 0.0 : u(rng);
        const double lambda = 360 + 470 * u(rng);
        if (n0 * std::sqrt(1 - cosI * cosI) > sub.real()) ++beyondCritical;
        const ThinFilmStackResult r = thinFilmStackRT(lambda, cosI, n0, layers, sub);
        EXPECT_NEAR(r.Rs + r.Ts, 1.0, 1e-10) << i;
        EXPECT_NEAR(r.Rp + r.Tp, 1.0, 1e-10) << i;
        const ThinFilmStackResult a = airySingleFilm(lambda, cosI, n0, layers[0], sub);
        EXPECT_NEAR(a.Rs + a.Ts, 1.0, 1e-10) << i;
        EXPECT_NEAR(a.Rp + a.Tp, 1.0, 1e-10) << i;
        const ThinFilmStackResult inc = incoherentSingleFilm(lambda, cosI, n0, layers[0], sub);
        EXPECT_NEAR(inc.Rs + inc.Ts, 1.0, 1e-10) << i;
        EXPECT_NEAR(inc.Rp + inc.Tp, 1.0, 1e-10) << i;
    }
    EXPECT_GT(beyondCritical, 300);  // the sample really covers total internal reflection
}

TEST(FilmStack, FrustratedTotalInternalReflection) {
    // Glass / air gap / glass at 60° (beyond the 41.8° critical angle): the evanescent gap tunnels
    // light for thin gaps and reflects totally for thick ones, without overflow (e^{−κd} form).
    const double n0 = 1.5, c = 0.5;
    const complexd sub(1.5, 0);
    double prevT = 2;
    for (double d : {0.0, 20.0, 100.0, 300.0, 1000.0, 1e4, 1e5}) {
        const Layer gap{complexd(1.0, 0), d};
        const ThinFilmStackResult tmm = thinFilmStackRT(500, c, n0, std::span(&gap, 1), sub);
        const ThinFilmStackResult airy = airySingleFilm(500, c, n0, gap, sub);
        EXPECT_TRUE(std::isfinite(tmm.R()) && std::isfinite(tmm.T()));
        EXPECT_NEAR(tmm.R() + tmm.T(), 1.0, 1e-12) << d;
        EXPECT_NEAR(airy.R(), tmm.R(), 1e-12) << d;
        EXPECT_NEAR(airy.T(), tmm.T(), 1e-12) << d;
        EXPECT_LT(tmm.T(), prevT);  // tunnelling decreases monotonically with the gap width
        prevT = tmm.T();
    }
    EXPECT_NEAR(prevT, 0.0, 1e-300);
    const Layer zero{complexd(1.0, 0), 0.0};
    EXPECT_NEAR(thinFilmStackRT(500, c, n0, std::span(&zero, 1), sub).T(), 1.0, 1e-12);
}

TEST(FilmStack, ThickAbsorbingLayerActsAsSemiInfiniteMedium) {
    // 100 µm of metal (k = 10) is opaque: R is the bare metal's, T underflows to exactly 0, no NaN.
    const complexd metal(1.3, 10.0);
    for (double c : {1.0, 0.6, 0.05}) {
        const Layer thick{metal, 1e5};
        const ThinFilmStackResult tmm = thinFilmStackRT(400, c, 1.0, std::span(&thick, 1), complexd(1.5, 0));
        const ThinFilmStackResult bare = fresnelInterfaceRT(c, 1.0, metal);
        EXPECT_NEAR(tmm.Rs, bare.Rs, 1e-13);
        EXPECT_NEAR(tmm.Rp, bare.Rp, 1e-13);
        EXPECT_EQ(tmm.T(), 0.0);
        const ThinFilmStackResult airy = airySingleFilm(400, c, 1.0, thick, complexd(1.5, 0));
        EXPECT_NEAR(airy.R(), bare.R(), 1e-13);
    }
    // A thin metal film transmits a little; Beer-Lambert-like decay with thickness.
    const Layer t10{metal, 10}, t20{metal, 20};
    const double T10 = thinFilmStackRT(500, 1, 1, std::span(&t10, 1), complexd(1.5, 0)).T();
    const double T20 = thinFilmStackRT(500, 1, 1, std::span(&t20, 1), complexd(1.5, 0)).T();
    EXPECT_GT(T10, 0.0);
    EXPECT_NEAR(T20 / T10, std::exp(-4 * kPiD * 10.0 * 10 / 500), 0.2 * T20 / T10);
}

TEST(FilmStack, TransferMatrixEqualsAiryForOneLayer) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(0, 1);
    for (int i = 0; i < 5000; ++i) {
        const double n0 = 1.0 + u(rng);
        const Layer film{complexd(1.0 + 3 * u(rng), u(rng) < 0.5 ? 0.0 : 2 * u(rng) * u(rng)), 3000 * u(rng) * u(rng)};
        const complexd sub(0.1 + 3 * u(rng), u(rng) < 0.5 ? 0.0 : 6 * u(rng));
        const double cosI = u(rng), lambda = 360 + 470 * u(rng);
        const ThinFilmStackResult t = thinFilmStackRT(lambda, cosI, n0, std::span(&film, 1), sub);
        const ThinFilmStackResult a = airySingleFilm(lambda, cosI, n0, film, sub);
        ASSERT_NEAR(t.Rs, a.Rs, 1e-10) << i;
        ASSERT_NEAR(t.Rp, a.Rp, 1e-10) << i;
        ASSERT_NEAR(t.Ts, a.Ts, 1e-10) << i;
        ASSERT_NEAR(t.Tp, a.Tp, 1e-10) << i;
    }
}

TEST(FilmStack, AiryMatchesRealFormulaForThickFilmsInLongDouble) {
    // Born & Wolf §1.6.4 for real indices at normal incidence, evaluated in long double as the
    // reference for phase accuracy of thick films: R = (r01² + r12² + 2 r01 r12 cos 2δ)/(1 + r01² r12² + 2 r01 r12 cos 2δ).
    const long double n0 = 1, n1 = 1.45, n2 = 1.9;
    const long double r01 = (n0 - n1) / (n0 + n1), r12 = (n1 - n2) / (n1 + n2);
    for (double d : {1e3, 1e4, 5e4, 1e5}) {
        for (double lambda : {360.0, 455.5, 612.25, 830.0}) {
            const long double twoDelta = 4.0L * 3.14159265358979323846264338327950288L * n1 * (long double)d / lambda;
            const long double c = std::cos(twoDelta);
            const long double R = (r01 * r01 + r12 * r12 + 2 * r01 * r12 * c) / (1 + r01 * r01 * r12 * r12 + 2 * r01 * r12 * c);
            const Layer film{complexd(1.45, 0), d};
            EXPECT_NEAR(airySingleFilm(lambda, 1.0, 1.0, film, complexd(1.9, 0)).R(), (double)R, 1e-11);
            EXPECT_NEAR(thinFilmStackRT(lambda, 1.0, 1.0, std::span(&film, 1), complexd(1.9, 0)).R(), (double)R, 1e-11);
        }
    }
}

TEST(FilmStack, ThickFilmWavelengthAverageTendsToIncoherentSum) {
    for (double k : {0.0, 2e-6}) {
        for (double cosI : {1.0, 0.5}) {
            const Layer film{complexd(1.5, k), 1e5};  // 100 µm
            const complexd sub(1.0, 0.0);               // free-standing-like: strong fringes (bubble)
            const complexd metal(0.2, 3.0);
            for (complexd s : {sub, metal}) {
                const int n = 40000;
                double sumR = 0, sumT = 0, sumInc = 0, sumIncT = 0;
                for (int i = 0; i < n; ++i) {
                    const double lambda = 500 + 100 * (i + 0.5) / n;  // ~100 fringes
                    const ThinFilmStackResult a = airySingleFilm(lambda, cosI, 1.0, film, s);
                    const ThinFilmStackResult inc = incoherentSingleFilm(lambda, cosI, 1.0, film, s);
                    sumR += a.R();
                    sumT += a.T();
                    sumInc += inc.R();
                    sumIncT += inc.T();
                }
                EXPECT_NEAR(sumR / n, sumInc / n, 2e-3) << k << " " << cosI;
                EXPECT_NEAR(sumT / n, sumIncT / n, 2e-3) << k << " " << cosI;
            }
        }
    }
    // A thin film is far from incoherent at a single wavelength (the test above can fail).
    const Layer thin{complexd(1.5, 0), 550 / (4 * 1.5)};  // quarter wave: coherent R = 0.148, incoherent 0.077
    EXPECT_GT(std::abs(airySingleFilm(550, 1, 1, thin, 1.0).R() - incoherentSingleFilm(550, 1, 1, thin, 1.0).R()), 0.05);
}

TEST(FilmStack, TruncatedSumConvergesToClosedForm) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(0, 1);
    const int kMaxK = 24, cases = 2000;
    std::vector<double> err(kMaxK + 1, 0.0);
    for (int i = 0; i < cases; ++i) {
        const double n0 = 1.0;
        const Layer film{complexd(1.2 + 2 * u(rng), u(rng) < 0.7 ? 0.0 : 0.3 * u(rng)), 1500 * u(rng)};
        const complexd sub(0.2 + 2.5 * u(rng), u(rng) < 0.5 ? 0.0 : 5 * u(rng));
        const double cosI = 0.05 + 0.95 * u(rng), lambda = 360 + 470 * u(rng);
        const ThinFilmStackResult ex = airySingleFilm(lambda, cosI, n0, film, sub);
        for (int K = 0; K <= kMaxK; ++K) {
            const ThinFilmStackResult tr = truncatedSingleFilm(lambda, cosI, n0, film, sub, K);
            err[K] += std::abs(tr.R() - ex.R()) + std::abs(tr.T() - ex.T());
        }
        // K → ∞: the closed form.
        const ThinFilmStackResult big = truncatedSingleFilm(lambda, cosI, n0, film, sub, 2000);
        EXPECT_NEAR(big.R(), ex.R(), 1e-9);
        EXPECT_NEAR(big.T(), ex.T(), 1e-9);
    }
    for (int K = 1; K <= kMaxK; ++K) EXPECT_LT(err[K], err[K - 1]) << K;
    EXPECT_LT(err[kMaxK] / cases, 0.02 * err[1] / cases);
    // K = 0 keeps only the top interface.
    const Layer f{complexd(1.7, 0), 200};
    EXPECT_NEAR(truncatedSingleFilm(500, 0.8, 1.0, f, 1.5, 0).R(), fresnelInterfaceRT(0.8, 1.0, 1.7).R(), 1e-14);
    EXPECT_EQ(truncatedSingleFilm(500, 0.8, 1.0, f, 1.5, 0).T(), 0.0);
    // K = 1 for a lossless film at normal incidence: (r01 + (1 − r01²) r12 e^{2iδ}) in real numbers.
    const double r01 = (1 - 1.7) / 2.7, r12 = (1.7 - 1.5) / 3.2, twoDelta = 4 * kPiD * 1.7 * 200 / 500;
    const double re = r01 + (1 - r01 * r01) * r12 * std::cos(twoDelta), im = (1 - r01 * r01) * r12 * std::sin(twoDelta);
    EXPECT_NEAR(truncatedSingleFilm(500, 1.0, 1.0, f, 1.5, 1).R(), re * re + im * im, 1e-14);
}

TEST(FilmStack, DenseGridIsFiniteAndBounded) {
    const std::vector<double> angles = {0, 10, 30, 45, 60, 75, 85, 89, 89.9, 89.99};
    const std::vector<double> etas = {1.0001, 1.2, 1.5, 2.0, 3.0, 4.0};
    const std::vector<double> ks = {0, 1e-4, 0.1, 1, 4, 10};
    const std::vector<double> ds = {0, 1, 50, 300, 1000, 1e4, 5e4, 1e5};
    const std::vector<double> lambdas = {360, 450, 550, 700, 830};
    const std::vector<complexd> subs = {{1.0, 0}, {1.5, 0}, {0.15, 3.6}, {2.9, 0.6}, {1.0001, 10}};
    const std::vector<double> incidents = {1.0, 1.6};
    long count = 0;
    for (double a : angles)
        for (double eta : etas)
            for (double k : ks)
                for (double d : ds)
                    for (double lambda : lambdas)
                        for (const complexd& sub : subs)
                            for (double n0 : incidents) {
                                const double c = std::cos(a * kPiD / 180);
                                const Layer film{complexd(eta, k), d};
                                const Layer stack[3] = {film, {complexd(1.38, 0), 100}, film};
                                const ThinFilmStackResult rs[4] = {
                                    thinFilmStackRT(lambda, c, n0, stack, sub), airySingleFilm(lambda, c, n0, film, sub),
                                    incoherentSingleFilm(lambda, c, n0, film, sub),
                                    truncatedSingleFilm(lambda, c, n0, film, sub, 3)};
                                for (int m = 0; m < 4; ++m) {
                                    const ThinFilmStackResult& r = rs[m];
                                    for (double v : {r.Rs, r.Rp, r.Ts, r.Tp}) {
                                        ASSERT_TRUE(std::isfinite(v)) << a << " " << eta << " " << k << " " << d;
                                        ASSERT_GE(v, 0.0);
                                        if (m < 3) {
                                            ASSERT_LE(v, 1.0);
                                        }
                                    }
                                    if (m < 3) {
                                        ASSERT_LE(r.Rs + r.Ts, 1.0 + 1e-9) << m << " " << a << " " << eta << " " << k << " " << d;
                                        ASSERT_LE(r.Rp + r.Tp, 1.0 + 1e-9) << m << " " << a << " " << eta << " " << k << " " << d;
                                    }
                                    ++count;
                                }
                            }
    EXPECT_EQ(count, 4L * 10 * 6 * 6 * 8 * 5 * 5 * 2);
}

TEST(FilmStack, FiftyLayerBraggMirror) {
    // Quarter-wave stack (HL)^N H... at normal incidence (Macleod, high-reflectance coatings): for 2N layers HL on ns,
    // R = ((1 − (ns/n0)(nH/nL)^{2N}) / (1 + (ns/n0)(nH/nL)^{2N}))².
    const double nH = 2.3, nL = 1.38, ns = 1.52, lambda = 600;
    for (int N : {1, 3, 5, 25}) {
        std::vector<Layer> layers;
        for (int i = 0; i < N; ++i) {
            layers.push_back({complexd(nH, 0), lambda / (4 * nH)});
            layers.push_back({complexd(nL, 0), lambda / (4 * nL)});
        }
        const double y = ns * std::pow(nH / nL, 2 * N);
        const double expected = std::pow((1 - y) / (1 + y), 2);
        const ThinFilmStackResult r = thinFilmStackRT(lambda, 1.0, 1.0, layers, complexd(ns, 0));
        EXPECT_NEAR(r.R(), expected, 1e-10) << N;
        EXPECT_NEAR(r.R() + r.T(), 1.0, 1e-10);
        // Oblique, off-design and absorbing variants stay finite and bounded.
        for (auto& l : layers) l.ior += complexd(0, 0.05);
        const ThinFilmStackResult ra = thinFilmStackRT(455, 0.3, 1.0, layers, complexd(0.2, 3.0));
        EXPECT_TRUE(std::isfinite(ra.R()) && std::isfinite(ra.T()));
        EXPECT_GE(ra.A(), -1e-12);
        EXPECT_LE(ra.R() + ra.T(), 1.0 + 1e-12);
    }
    // 50 thick absorbing layers: T underflows to 0 without NaN.
    std::vector<Layer> thick(50, Layer{complexd(2.0, 0.5), 2e4});
    const ThinFilmStackResult r = thinFilmStackRT(500, 0.7, 1.0, thick, complexd(1.5, 0));
    EXPECT_TRUE(std::isfinite(r.R()));
    EXPECT_EQ(r.T(), 0.0);
    EXPECT_NEAR(r.R(), fresnelInterfaceRT(0.7, 1.0, complexd(2.0, 0.5)).R(), 1e-12);
}

}  // namespace
}  // namespace iris
