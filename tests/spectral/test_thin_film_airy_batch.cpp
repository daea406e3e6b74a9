// The batched Airy kernel (spectral/thin_film_airy_batch.h), which ThinFilmCoating evaluates all wavelengths
// of a path through, against the scalar kernel airySingleFilmFastAt lane by lane: the same decline
// decisions everywhere, bit-identical R and T where both square roots are real (lossless film and
// substrate: the same operations in the same order), and agreement to rounding where a radicand is
// complex (the batch takes the principal root by Kahan's formula, the scalar one glibc's csqrt).
// Then ThinFilmCoating's batched reflectance / transmittance against its per-entry stackRT.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/arena.h"
#include "spectral/thin_film_airy.h"
#include "spectral/thin_film_airy_batch.h"
#include "spectral/thin_film_polarization.h"
#include "materials/thin_film_coating.h"
#include "spectral/lane_dispatch.h"
#include "tests/support/bsdf_test_util.h"

namespace iris {
namespace {

struct LaneCase {
    AiryAngle angle;
    AiryFilmConstants film;
    SquaredIndex substrate;
    bool lossless = false;
};

/// Random lanes covering the kernel's branches: lossless and absorbing films and substrates,
/// incidence below and beyond total internal reflection (incident media denser than the film),
/// grazing and normal incidence, zero thickness, and films so thick that the phase exceeds the
/// polynomial sin/cos range (|δ| > 1e5: the libm fallback lanes).
LaneCase randomLane(std::mt19937& rng) {
    std::uniform_real_distribution<double> U(0.0, 1.0);
    const double n0 = U(rng) < 0.3 ? 1.0 + 1.5 * U(rng) : 1.0;
    const double cosGrid[] = {1.0, 0.0, 1e-9, 1e-4, 0.5};
    const double c = U(rng) < 0.2 ? cosGrid[int(U(rng) * 5) % 5] : U(rng);
    const double n1 = 1.0 + 2.0 * U(rng), k1 = U(rng) < 0.6 ? 0.0 : 2.0 * U(rng) * U(rng);
    const bool conductor = U(rng) < 0.4;
    const double n2 = conductor ? 0.1 + 2.0 * U(rng) : 1.0 + 2.0 * U(rng);
    const double k2 = conductor ? 5.0 * U(rng) : (U(rng) < 0.8 ? 0.0 : 0.1 * U(rng));
    const double r = U(rng);
    const double d = r < 0.05 ? 0.0 : r < 0.1 ? 2e7 * U(rng) : 2000.0 * U(rng);  // nm
    const double lambda = 360.0 + 470.0 * U(rng);
    LaneCase l;
    l.angle = airyAngle(c, n0);
    l.film = airyFilmConstants(lambda, d, squaredIndex(complexd(n1, k1)));
    l.substrate = squaredIndex(complexd(n2, k2));
    l.lossless = k1 == 0 && k2 == 0;
    return l;
}

struct Batch {
    double v[12][kMaxWavelengths];
    double out[4][kMaxWavelengths];
    void set(int k, const LaneCase& l) {
        const double x[12] = {l.film.n1sq.real(), l.film.n1sq.imag(), l.film.invN1sq.real(), l.film.invN1sq.imag(),
                              l.film.k0d, l.substrate.sq.real(), l.substrate.sq.imag(), l.substrate.inv.real(),
                              l.substrate.inv.imag(), l.angle.s2, l.angle.y0s, l.angle.y0p};
        for (int a = 0; a < 12; ++a) v[a][k] = x[a];
    }
    /// Random lanes for entries [0, airyPadded(n)), their cases in lanes[].
    void fillRandom(std::mt19937& rng, int n, LaneCase* lanes) {
        for (int k = 0; k < airyPadded(n); ++k) {
            lanes[k] = randomLane(rng);
            set(k, lanes[k]);
        }
    }
    uint32_t run(int n) {
        const AiryBatchInput in{v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8], v[9], v[10], v[11]};
        return airySingleFilmBatch(in, n, AiryBatchOutput{out[0], out[1], out[2], out[3]});
    }
};

TEST(FilmAiryBatch, EveryLaneEqualsTheScalarKernel) {
    std::mt19937 rng(20261201);
    long lossless = 0, complexLanes = 0, declined = 0;
    double maxComplexDiff = 0;
    for (int trial = 0; trial < 20000; ++trial) {
        const int n = 1 + trial % kMaxWavelengths;
        Batch b;
        LaneCase lanes[kMaxWavelengths];
        b.fillRandom(rng, n, lanes);
        const uint32_t mask = b.run(n);
        if (n < 32) ASSERT_EQ(mask >> n, 0u) << "lanes beyond n reported";
        for (int k = 0; k < n; ++k) {
            ThinFilmStackResult s;
            const bool ok = airySingleFilmFastAt(lanes[k].angle, lanes[k].film, lanes[k].substrate, s);
            ASSERT_EQ(ok, !(mask >> k & 1)) << "trial " << trial << " lane " << k;
            if (!ok) {
                ++declined;
                continue;
            }
            const double got[4] = {b.out[0][k], b.out[1][k], b.out[2][k], b.out[3][k]};
            const double want[4] = {s.Rs, s.Rp, s.Ts, s.Tp};
            for (int q = 0; q < 4; ++q) {
                if (lanes[k].lossless) {
                    ASSERT_EQ(got[q], want[q]) << "lossless lane, trial " << trial << " lane " << k << " output " << q;
                } else {
                    maxComplexDiff = std::max(maxComplexDiff, std::abs(got[q] - want[q]));
                }
            }
            ++(lanes[k].lossless ? lossless : complexLanes);
        }
    }
    EXPECT_LE(maxComplexDiff, 1e-12);
    // The random cases reach both kinds of lanes in numbers.
    EXPECT_GT(lossless, 50000);
    EXPECT_GT(complexLanes, 50000);
    std::cout << "lossless lanes " << lossless << ", complex lanes " << complexLanes << " (max |diff| "
              << maxComplexDiff << "), declined " << declined << "\n";
}

// The polarized mode's terms (AiryBatchOutput with crossR, crossT) against the scalar
// clampedPolarization(airySingleFilmPolarizationAt(...)) lane by lane, over the same random lanes:
// bit-identical where both square roots are real, to rounding elsewhere.
TEST(FilmAiryBatch, CrossTermsEqualTheScalarPolarizationKernel) {
    std::mt19937 rng(20261207);
    long compared = 0;
    double maxComplexDiff = 0;
    for (int trial = 0; trial < 5000; ++trial) {
        const int n = 1 + trial % kMaxWavelengths;
        Batch b;
        LaneCase lanes[kMaxWavelengths];
        b.fillRandom(rng, n, lanes);
        double cross[4][kMaxWavelengths];
        const AiryBatchInput in{b.v[0], b.v[1], b.v[2], b.v[3], b.v[4], b.v[5], b.v[6], b.v[7], b.v[8], b.v[9], b.v[10], b.v[11]};
        const uint32_t mask = airySingleFilmBatch(
            in, n, AiryBatchOutput{b.out[0], b.out[1], b.out[2], b.out[3], cross[0], cross[1], cross[2], cross[3]});
        for (int k = 0; k < n; ++k) {
            FilmPolarization p;
            const bool ok = airySingleFilmPolarizationAt(lanes[k].angle, lanes[k].film, lanes[k].substrate, p);
            ASSERT_EQ(ok, !(mask >> k & 1)) << "trial " << trial << " lane " << k;
            if (!ok) continue;
            p = clampedPolarization(p);
            const double got[8] = {b.out[0][k], b.out[1][k], b.out[2][k], b.out[3][k], cross[0][k], cross[1][k], cross[2][k], cross[3][k]};
            const double want[8] = {p.power.Rs, p.power.Rp, p.power.Ts, p.power.Tp,
                                    p.crossR.real(), p.crossR.imag(), p.crossT.real(), p.crossT.imag()};
            for (int q = 0; q < 8; ++q) {
                if (lanes[k].lossless)
                    ASSERT_EQ(got[q], want[q]) << "lossless lane, trial " << trial << " lane " << k << " output " << q;
                else
                    maxComplexDiff = std::max(maxComplexDiff, std::abs(got[q] - want[q]));
            }
            ++compared;
        }
    }
    EXPECT_LE(maxComplexDiff, 1e-12);
    EXPECT_GT(compared, 50000);
}

TEST(FilmAiryBatch, BaselineAndAvx2BuildsAgreeBitForBit) {
    if (!lanes::useAvx2()) GTEST_SKIP() << "this CPU has no AVX2: only the baseline build runs";
    std::mt19937 rng(42);
    for (int trial = 0; trial < 3000; ++trial) {
        const int n = 1 + trial % kMaxWavelengths;
        Batch a;
        for (int k = 0; k < airyPadded(n); ++k) a.set(k, randomLane(rng));
        Batch b = a;
        const uint32_t ma = a.run(n);
        lanes::forceBaseline = true;
        const uint32_t mb = b.run(n);
        lanes::forceBaseline = false;
        ASSERT_EQ(ma, mb);
        for (int q = 0; q < 4; ++q)
            for (int k = 0; k < n; ++k)
                if (!(ma >> k & 1)) ASSERT_EQ(a.out[q][k], b.out[q][k]) << "trial " << trial << " lane " << k;
    }
}

TEST(FilmAiryBatch, DeclinedLanesAreReported) {
    // q1 = 0 exactly (s = n1: incidence at the film's critical angle from a denser medium, with
    // d = 0 so that nothing else is degenerate): the scalar kernel returns false; so must the batch
    // lane, and only that lane.
    std::mt19937 rng(7);
    Batch b;
    LaneCase lanes[8];
    for (int k = 0; k < 8; ++k) {
        lanes[k] = randomLane(rng);
        lanes[k].lossless = true;
    }
    const double n0 = 2.0, n1 = 1.5;
    lanes[5].angle = airyAngle(std::sqrt(1.0 - (n1 / n0) * (n1 / n0)), n0);
    lanes[5].angle.s2 = n1 * n1;  // exactly
    lanes[5].film = airyFilmConstants(500.0, 0.0, squaredIndex(complexd(n1, 0.0)));
    lanes[5].substrate = squaredIndex(complexd(n1, 0.0));
    ThinFilmStackResult s;
    ASSERT_FALSE(airySingleFilmFastAt(lanes[5].angle, lanes[5].film, lanes[5].substrate, s));
    for (int k = 0; k < 8; ++k) b.set(k, lanes[k]);
    uint32_t expected = 0;
    for (int k = 0; k < 7; ++k)
        if (!airySingleFilmFastAt(lanes[k].angle, lanes[k].film, lanes[k].substrate, s)) expected |= 1u << k;
    EXPECT_EQ(b.run(7), expected | (1u << 5));
}

// ThinFilmCoating's reflectance / reflectanceTransmittance / fromBelowRT (batched) against stackRT and
// stackRTFromBelow at each entry (the scalar kernel): gold (complex substrate) and dielectric
// substrates, absorbing and lossless films, every count of wavelengths.
TEST(FilmAiryBatch, ThinFilmCoatingBatchedEqualsPerEntry) {
    struct Case {
        const char* what;
        std::shared_ptr<Properties> props;
        bool transmission;
    };
    const std::vector<Case> cases = {
        {"lossless film on glass",
         test::makeProps("thinfilm", {{"film_ior", 2.3f}, {"thickness", 420.0f}, {"substrate_eta", 1.52f}}), true},
        {"absorbing film on glass",
         test::makeProps("thinfilm", {{"film_ior", 1.8f}, {"film_k", 0.05f}, {"thickness", 250.0f}, {"substrate_eta", 1.4f}}),
         true},
        {"film on gold",
         test::makeProps("thinfilm", {{"film_ior", 1.45f}, {"thickness", 320.0f}, {"substrate_material", std::string("Au")}}),
         false},
    };
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> U(0.0f, 1.0f);
    for (const Case& c : cases) {
        const ThinFilmCoatingSpec spec = ThinFilmCoatingSpec::fromProperties(*c.props, 1.5f, 0.0f);
        for (int n = 1; n <= kMaxWavelengths; ++n) {
            const SampledWavelengths wl = SampledWavelengths::sampleVisible(U(rng), n);
            Arena arena;
            const ThinFilmCoating coat(spec, TextureQuery{}, wl, arena);
            for (float cosTheta : {1.0f, 0.73f, 0.2f, 1e-3f, 0.0f, U(rng)}) {
                const SampledSpectrum R = coat.reflectance(cosTheta);
                SampledSpectrum R2, T2, Rb, Tb;
                coat.reflectanceTransmittance(cosTheta, R2, T2);
                if (c.transmission) coat.fromBelowRT(cosTheta, Rb, Tb);
                for (int k = 0; k < n; ++k) {
                    const ThinFilmStackResult a = coat.stackRT(k, cosTheta);
                    // Float outputs: the scalar and batched double results agree to 1e-12, far
                    // below a float ulp, so they round to the same or an adjacent float.
                    EXPECT_NEAR(R[k], float(a.R()), 1e-7f) << c.what << " n " << n << " k " << k;
                    EXPECT_EQ(R2[k], R[k]);
                    EXPECT_NEAR(T2[k], float(a.T()), 1e-7f) << c.what << " n " << n << " k " << k;
                    if (c.transmission) {
                        const ThinFilmStackResult b = coat.stackRTFromBelow(k, cosTheta);
                        EXPECT_NEAR(Rb[k], float(b.R()), 1e-7f) << c.what << " below, n " << n << " k " << k;
                        EXPECT_NEAR(Tb[k], float(b.T()), 1e-7f) << c.what << " below, n " << n << " k " << k;
                    }
                }
            }
        }
    }
}

}  // namespace

// ThinFilmCoating::polarizationAll / polarizationPowersAll (the batched kernel) against the
// per-entry polarization / polarizationPowers, from above and below, on an absorbing film over
// glass and a film on gold.
TEST(FilmAiryBatch, CoatingPolarizationAllEqualsPerEntry) {
    const std::vector<std::pair<const char*, std::shared_ptr<Properties>>> cases = {
        {"absorbing film on glass",
         test::makeProps("thinfilm", {{"film_ior", 1.8f}, {"film_k", 0.05f}, {"thickness", 250.0f}, {"substrate_eta", 1.4f}})},
        {"film on gold",
         test::makeProps("thinfilm", {{"film_ior", 1.45f}, {"thickness", 320.0f}, {"substrate_material", std::string("Au")}})},
    };
    for (const auto& [what, props] : cases) {
        const ThinFilmCoatingSpec spec = ThinFilmCoatingSpec::fromProperties(*props, 1.5f, 0.0f);
        for (int n : {1, 4, 7, 16}) {
            const SampledWavelengths wl = SampledWavelengths::sampleVisible(0.37f, n);
            Arena arena;
            const ThinFilmCoating coat(spec, TextureQuery{}, wl, arena);
            for (double cosTheta : {1.0, 0.6, 0.05, 0.0})
                for (bool below : {false, true}) {
                    if (below && std::string(what) == "film on gold") continue;  // an opaque substrate is not lit from below
                    ThinFilmCoating::PolarizationLanes all, powers;
                    coat.polarizationAll(cosTheta, below, all);
                    coat.polarizationPowersAll(cosTheta, below, powers);
                    for (int k = 0; k < n; ++k) {
                        const FilmPolarization one = coat.polarization(k, cosTheta, below);
                        const ThinFilmStackResult p = coat.polarizationPowers(k, cosTheta, below);
                        const double got[8] = {all.Rs[k], all.Rp[k], all.Ts[k], all.Tp[k],
                                               all.crossRRe[k], all.crossRIm[k], all.crossTRe[k], all.crossTIm[k]};
                        const double want[8] = {one.power.Rs, one.power.Rp, one.power.Ts, one.power.Tp,
                                                one.crossR.real(), one.crossR.imag(), one.crossT.real(), one.crossT.imag()};
                        for (int q = 0; q < 8; ++q) EXPECT_NEAR(got[q], want[q], 1e-12) << what << " n " << n << " k " << k << " q " << q;
                        EXPECT_NEAR(powers.Rs[k], p.Rs, 1e-12);
                        EXPECT_NEAR(powers.Rp[k], p.Rp, 1e-12);
                        EXPECT_NEAR(powers.Ts[k], p.Ts, 1e-12);
                        EXPECT_NEAR(powers.Tp[k], p.Tp, 1e-12);
                    }
                }
        }
    }
}

}  // namespace iris
