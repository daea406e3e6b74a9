// The fast exact Airy path (spectral/thin_film_stack.h airySingleFilmFast, used by airySingleFilm and by
// ThinFilmCoating with hoisted per-wavelength constants) against the original complex formulation
// (airySingleFilmReference) over many angles — including grazing incidence and cosines within
// 1e-3 … 1e-12 of every critical angle —, thicknesses, film and substrate indices and incident media.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "core/arena.h"
#include "spectral/thin_film_airy.h"
#include "materials/thin_film_coating.h"
#include "spectral/thin_film_stack.h"
#include "spectral/ior_params.h"
#include "tests/support/bsdf_test_util.h"

namespace iris {
namespace {

/// Cosines: a regular grid, grazing ones, and values just above/below/at the critical cosines of
/// the incident medium n0 against each of the given real indices.
std::vector<double> testCosines(double n0, std::initializer_list<double> others) {
    std::vector<double> c = {1.0, 0.999999, 0.9, 0.7, 0.5, 0.3, 0.1, 0.02, 1e-3, 1.745e-4, 1e-6, 1e-9, 0.0};
    for (double n : others) {
        if (!(n < n0)) continue;
        const double cc = std::sqrt(1.0 - (n / n0) * (n / n0));  // cosθ at which s = n
        c.push_back(cc);
        for (double e = 1e-3; e > 1e-13; e *= 0.1) {
            c.push_back(cc * (1 + e));
            c.push_back(cc * (1 - e));
        }
    }
    return c;
}

struct Diff {
    double maxR = 0, maxT = 0;
    long fast = 0, total = 0;
    void add(const ThinFilmStackResult& a, const ThinFilmStackResult& b) {
        maxR = std::max({maxR, std::abs(a.Rs - b.Rs), std::abs(a.Rp - b.Rp)});
        maxT = std::max({maxT, std::abs(a.Ts - b.Ts), std::abs(a.Tp - b.Tp)});
    }
};

double maxAbsDiff(const ThinFilmStackResult& a, const ThinFilmStackResult& b) {
    return std::max({std::abs(a.Rs - b.Rs), std::abs(a.Rp - b.Rp), std::abs(a.Ts - b.Ts), std::abs(a.Tp - b.Tp)});
}
bool allFinite(const ThinFilmStackResult& r) {
    return std::isfinite(r.Rs) && std::isfinite(r.Rp) && std::isfinite(r.Ts) && std::isfinite(r.Tp);
}

// The fast path against the general path (the transfer matrix, well conditioned at grazing and
// critical angles) and against the original r01/r12 formulation. The latter loses digits at the
// film's critical angle (q1 → 0: its r = (r01 + r12 E)/(1 + r01 r12 E) is 0/0 there, errors up to
// ~1e-8 against the TMM) and at grazing incidence, so it is held to 1e-11 plus its own distance
// from the TMM.
TEST(ThinFilmFastPath, AiryFastEqualsGeneralPathOnDenseGrid) {
    const double lambdas[] = {360.0, 455.0, 550.0, 671.0, 830.0};
    const double thick[] = {0.0, 1e-3, 1.0, 57.0, 250.0, 320.0, 1000.0, 1e4, 1e5};
    const double filmN[] = {1.0001, 1.33, 1.45, 1.9, 2.3, 4.0};
    const double filmK[] = {0.0, 1e-6, 1e-3, 0.1, 1.0, 10.0};
    const complexd subs[] = {{1.0, 0.0}, {1.0001, 0.0}, {1.5, 0.0}, {4.0, 0.0},
                             {0.15, 3.6}, {2.9, 0.6}, {0.2, 0.0}, {1.0001, 10.0}};
    long total = 0, fast = 0, refNaN = 0;
    double maxTmm = 0, maxRef = 0, maxRefExcess = 0;
    std::string worstCase;
    for (double n0 : {1.0, 1.33, 1.6, 4.0}) {
        for (double n1 : filmN) {
            for (const complexd& sub : subs) {
                for (double c : testCosines(n0, {n1, sub.real()})) {
                    for (double k1 : filmK) {
                        for (double t : thick) {
                            for (double l : lambdas) {
                                const Layer film{complexd(n1, k1), t};
                                ThinFilmStackResult f;
                                const bool ok = airySingleFilmFast(c, n0, airyFilmConstants(l, film), squaredIndex(sub), f);
                                const ThinFilmStackResult pub = airySingleFilm(l, c, n0, film, sub);
                                const ThinFilmStackResult tmm = thinFilmStackRT(l, c, n0, std::span(&film, 1), sub);
                                const ThinFilmStackResult ref = airySingleFilmReference(l, c, n0, film, sub);
                                ++total;
                                ASSERT_TRUE(allFinite(pub)) << "n0 " << n0 << " film " << n1 << "+" << k1 << "i d " << t
                                                            << " sub " << sub << " cos " << c << " λ " << l;
                                if (!ok) {  // declined: the public function is then the transfer matrix
                                    EXPECT_EQ(maxAbsDiff(pub, tmm), 0.0);
                                    // Only where the closed form itself is degenerate: q1 = 0, or a 0/0 of
                                    // the reference (cosθ = 0 with q2 = 0 and d = 0).
                                    const double cc = std::clamp(c, 0.0, 1.0);
                                    const double sInv = n0 * std::sqrt(std::max(0.0, 1.0 - cc * cc));
                                    EXPECT_TRUE(normalWaveNumber(film.ior, sInv) == complexd(0.0, 0.0) || !allFinite(ref))
                                        << "n0 " << n0 << " film " << n1 << "+" << k1 << "i d " << t << " sub " << sub
                                        << " cos " << c << " λ " << l;
                                    if (!allFinite(ref)) ++refNaN;
                                    continue;
                                }
                                ++fast;
                                EXPECT_EQ(maxAbsDiff(pub, f), 0.0);
                                const double eT = maxAbsDiff(f, tmm);
                                if (eT > maxTmm) {
                                    maxTmm = eT;
                                    std::ostringstream os;
                                    os << "n0 " << n0 << " film " << n1 << "+" << k1 << "i d " << t << " sub " << sub
                                       << " cos " << c << " λ " << l;
                                    worstCase = os.str();
                                }
                                ASSERT_TRUE(allFinite(ref));
                                const double eR = maxAbsDiff(f, ref);
                                maxRef = std::max(maxRef, eR);
                                maxRefExcess = std::max(maxRefExcess, eR - maxAbsDiff(ref, tmm));
                            }
                        }
                    }
                }
            }
        }
    }
    std::printf("FILM-FAST airy: %ld cases, fast path taken in %ld; max |fast - TMM| %.3g (%s); max |fast - "
                "reference| %.3g, minus |reference - TMM| at most %.3g; reference not finite in %ld cases (the fast path declined them, the TMM is finite there)\n",
                total, fast, maxTmm, worstCase.c_str(), maxRef, maxRefExcess, refNaN);
    EXPECT_LE(maxTmm, 1e-11);
    EXPECT_LE(maxRefExcess, 1e-11);
    // The grid deliberately holds q1 = 0 points (cosθ = 0 with n1 = n0, exact critical cosines);
    // everything else takes the fast path.
    EXPECT_GE(fast, total - total / 100);
}

TEST(ThinFilmFastPath, RandomCasesAgreeTightly) {
    std::mt19937 rng(20261201);
    std::uniform_real_distribution<double> u(0, 1);
    Diff d;
    double maxTmm = 0;
    for (int i = 0; i < 200000; ++i) {
        const double n0 = u(rng) < 0.5 ? 1.0 : 1.0 + 2 * u(rng);
        const Layer film{complexd(1.0 + 3 * u(rng), u(rng) < 0.5 ? 0.0 : std::pow(10.0, -6 + 7 * u(rng))),
                         u(rng) < 0.1 ? 0.0 : std::pow(10.0, -1 + 6 * u(rng))};
        const complexd sub = u(rng) < 0.5 ? complexd(0.1 + 3 * u(rng), 0.0) : complexd(0.1 + 3 * u(rng), 8 * u(rng));
        const double c = u(rng) < 0.05 ? 0.0 : u(rng);
        const double l = 360 + 470 * u(rng);
        ThinFilmStackResult fast;
        ++d.total;
        if (!airySingleFilmFast(c, n0, airyFilmConstants(l, film), squaredIndex(sub), fast)) continue;
        ++d.fast;
        d.add(fast, airySingleFilmReference(l, c, n0, film, sub));
        const ThinFilmStackResult tmm = thinFilmStackRT(l, c, n0, std::span(&film, 1), sub);
        maxTmm = std::max(maxTmm, maxAbsDiff(fast, tmm));
    }
    std::printf("FILM-FAST random: %ld cases, fast %ld, vs reference max |dR| %.3g, max |dT| %.3g; vs TMM %.3g\n",
                d.total, d.fast, d.maxR, d.maxT, maxTmm);
    EXPECT_EQ(d.fast, d.total);
    EXPECT_LE(maxTmm, 1e-12);
    EXPECT_LE(d.maxR, 1e-12);
    EXPECT_LE(d.maxT, 1e-12);
}

TEST(ThinFilmFastPath, DegenerateDenominatorFallsBackToTransferMatrix) {
    // q1 = 0 exactly: grazing incidence (s = n0 = 1) onto a film of index 1 — den = 0 in the closed
    // form; the fast path declines and airySingleFilm returns the transfer matrix.
    const Layer film{complexd(1.0, 0.0), 300.0};
    ThinFilmStackResult fast;
    EXPECT_FALSE(airySingleFilmFast(0.0, 1.0, airyFilmConstants(550.0, film), squaredIndex(complexd(1.5, 0.0)), fast));
    const ThinFilmStackResult pub = airySingleFilm(550.0, 0.0, 1.0, film, complexd(1.5, 0.0));
    const ThinFilmStackResult tmm = thinFilmStackRT(550.0, 0.0, 1.0, std::span(&film, 1), complexd(1.5, 0.0));
    EXPECT_EQ(maxAbsDiff(pub, tmm), 0.0);
    EXPECT_TRUE(allFinite(pub));
}

/// ThinFilmCoating (hoisted constants per path) against the reference evaluated from scratch, from
/// both sides, at N = 32 wavelengths and in RGB mode.
TEST(ThinFilmFastPath, ThinFilmCoatingUsesHoistedConstantsExactly) {
    for (float sub : {1.0f, 1.52f}) {
        for (float film : {1.33f, 2.3f}) {
            auto p = test::makeProps("thinfilm", {{"film_ior", film}, {"thickness", 380.0f}, {"substrate_eta", sub}});
            ThinFilmCoatingSpec spec = ThinFilmCoatingSpec::fromProperties(*p, 1.5f, 0.0f);
            Arena arena;
            float lambdas[kMaxWavelengths];
            for (int k = 0; k < kMaxWavelengths; ++k) lambdas[k] = 360.0f + 470.0f * (k + 0.37f) / kMaxWavelengths;
            const ThinFilmCoating coat(spec, TextureQuery{}, lambdas, kMaxWavelengths, arena);
            double maxDiff = 0;
            for (double c : testCosines(1.0, {})) {
                for (int k = 0; k < kMaxWavelengths; ++k) {
                    const Layer layer{complexd(film, 0.0), 380.0};
                    const ThinFilmStackResult a = coat.stackRT(k, c);
                    const ThinFilmStackResult r = airySingleFilmReference(lambdas[k], c, 1.0, layer, coat.substrateIor(k));
                    const ThinFilmStackResult b = coat.stackRTFromBelow(k, c);
                    const ThinFilmStackResult rb = airySingleFilmReference(lambdas[k], c, coat.substrateIor(k).real(), layer,
                                                                       complexd(1.0, 0.0));
                    maxDiff = std::max({maxDiff, std::abs(a.R() - r.R()), std::abs(a.T() - r.T()),
                                        std::abs(b.R() - rb.R()), std::abs(b.T() - rb.T())});
                }
            }
            EXPECT_LE(maxDiff, 1e-12) << "substrate " << sub << " film " << film;
        }
    }
}


/// The per-BSDF reuse of stack results (iridescent_diffuse: the stack at cosθo; thinfilm rough
/// transmission: the last (side, cosθ)) must not change any value: an interleaved sequence of
/// eval / pdf / sample calls on one BSDF equals the same calls each made on a fresh BSDF.
TEST(ThinFilmFastPath, StackReuseInBSDFsChangesNothing) {
    const SampledWavelengths wl = SampledWavelengths::sampleVisible(0.37f, 16);
    auto tProps = test::makeProps("thinfilm", {{"substrate", std::string("dielectric")}, {"film_ior", 1.33f},
                                               {"alpha", 0.2f}, {"thickness", 380.0f}, {"substrate_eta", 1.4f}});
    tProps->set("transmission", true, {});
    std::vector<std::shared_ptr<Properties>> configs = {
        test::makeProps("iridescent_diffuse", {{"film_ior", 1.9f}, {"thickness", 250.0f}, {"reflectance", 0.6f}}),
        test::makeProps("iridescent_diffuse", {{"film_ior", 1.6f}, {"thickness", 800.0f}, {"alpha", 0.2f}}),
        tProps};
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(0, 1);
    auto randomDir = [&](bool upper) {
        const float z = upper ? 0.02f + 0.98f * u(rng) : 2 * u(rng) - 1, phi = 6.2831853f * u(rng);
        const float r = std::sqrt(std::max(0.0f, 1 - z * z));
        return vec3(r * std::cos(phi), r * std::sin(phi), z);
    };
    for (const auto& props : configs) {
        const test::BSDFInstance reused = test::makeBSDF(*props, wl);
        const bool twoSided = props->type() == "thinfilm";
        for (int i = 0; i < 300; ++i) {
            const vec3 wo = randomDir(!twoSided), wi = randomDir(!twoSided);
            const float uc = u(rng);
            const vec2 us(u(rng), u(rng));
            for (int call = 0; call < 3; ++call) {  // the path tracer's order: eval, pdf, sample
                Arena arena;
                SampledWavelengths wlFresh = wl;
                struct {
                    const BSDF* bsdf;
                } fresh{reused.material->getBSDF(ShadingPoint{}, wlFresh, arena)};
                if (call == 0) {
                    const SampledSpectrum a = reused.bsdf->eval(wo, wi, TransportMode::Radiance);
                    const SampledSpectrum b = fresh.bsdf->eval(wo, wi, TransportMode::Radiance);
                    for (int k = 0; k < wl.size(); ++k) ASSERT_EQ(a[k], b[k]);
                } else if (call == 1) {
                    ASSERT_EQ(reused.bsdf->pdf(wo, wi, TransportMode::Radiance),
                              fresh.bsdf->pdf(wo, wi, TransportMode::Radiance));
                } else {
                    const auto a = reused.bsdf->sample(wo, uc, us, TransportMode::Radiance);
                    const auto b = fresh.bsdf->sample(wo, uc, us, TransportMode::Radiance);
                    ASSERT_EQ(bool(a), bool(b));
                    if (!a) continue;
                    ASSERT_EQ(a->pdf, b->pdf);
                    ASSERT_EQ(a->wi, b->wi);
                    for (int k = 0; k < wl.size(); ++k) ASSERT_EQ(a->f[k], b->f[k]);
                }
            }
        }
    }
}


TEST(ThinFilmFastPath, ConstantIndexIsExactAtEveryWavelength) {
    // A float index is a triple of equal values; it must come back unchanged at every λ (a lerp of
    // it rounded, which made substrate_eta = 1.4 fail the non-dispersive check of transmission).
    auto p = test::makeProps("thinfilm", {{"substrate_eta", 1.4f}, {"film_ior", 1.33f}});
    const IOR eta = readIOR(*p, "substrate_eta", IOR::constant(1.5f));
    for (float l = 360.0f; l <= 830.0f; l += 0.37f) ASSERT_EQ(eta.eval(l), 1.4f) << l;
    p->set("substrate", std::string("dielectric"), {});
    p->set("transmission", true, {});
    EXPECT_NO_THROW(test::makeBSDF(*p, SampledWavelengths::sampleVisible(0.5f, 8)));
}


TEST(ThinFilmFastPath, SinCosMatchesLibm) {
    // The inline sin/cos of the Airy phase against glibc over the phases films produce (|x| up to
    // 1e5, i.e. 2π·4·100 µm/360 nm ≈ 7e3 with margin), near multiples of π/2 and beyond the range.
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(0, 1);
    double maxErr = 0;
    auto check = [&](double x) {
        double s, c;
        airy_detail::sinCos(x, s, c);
        maxErr = std::max({maxErr, std::abs(s - std::sin(x)), std::abs(c - std::cos(x))});
    };
    for (int i = 0; i < 1000000; ++i) check((u(rng) < 0.5 ? 1.0 : -1.0) * std::pow(10.0, -8 + 13 * u(rng)));
    for (int j = -70000; j <= 70000; j += 7)
        for (double e : {0.0, 1e-12, -1e-9, 1e-6, 0.3, -0.7853981})
            check(j * 1.5707963267948966 + e);
    for (double x : {0.0, -0.0, 1e5, -1e5, 1.0000001e5, 3e7, 1e300}) check(x);
    std::printf("FILM-FAST sinCos: max |error| vs glibc %.3g\n", maxErr);
    EXPECT_LE(maxErr, 4e-16);
    double s, c;
    airy_detail::sinCos(std::numeric_limits<double>::quiet_NaN(), s, c);
    EXPECT_TRUE(std::isnan(s) && std::isnan(c));
}

}  // namespace
}  // namespace iris
