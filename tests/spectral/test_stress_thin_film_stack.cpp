// Numerical stress of the thin-film stack optics (spectral/thin_film_stack.h; issue 7, docs/numerics.md).
//
//  * DenseSingleFilmGrid: Airy (exact, incoherent, truncated K = 8) and the transfer-matrix method
//    over a dense grid — angles 0 … 89.99°, film η 1.0001 … 4, k 0 … 10, thickness 0 … 1e5 nm,
//    λ 360 … 830 nm, dielectric/absorbing substrates, incident medium 1 and 1.6 (total internal
//    reflection): finite, R, T ∈ [0, 1], R + T ≤ 1, lossless stacks conserve energy
//    (|R + T − 1| measured), and the Airy closed form agrees with the transfer matrix.
//  * RandomFiftyLayerStacks: random stacks of up to 50 layers (fixed seed) with the same ranges.
//  * FloatAiryAgainstDouble: the library has no float evaluation path, so this test carries a
//    templated copy of the single-film Airy formula (Born & Wolf §7.6.1, eqs. 7.6(14)–(15), in the
//    admittance form of Macleod §2.2), checks its double instance against airySingleFilm and
//    measures how far its float instance drifts — per thickness range, since the phase error
//    grows with δ = 2π ñ d cosθ/λ.
//  * FloatPhaseTerm: the float phase term cos(2Φ), Φ = π η d/λ (cosθti + cosθto), of the granier
//    and proposed materials (thesis 000 eq. 2.28 / 3.20) against double.
// Measured maxima are printed as "FILM-STRESS" lines (copied into docs/numerics.md).
// Counts scale with IRIS_STRESS_SCALE (default 1; 0.1 under ASan).
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstdlib>
#include <iomanip>
#include <random>
#include <sstream>
#include <vector>

#include "spectral/thin_film_stack.h"

using namespace iris;

namespace {

#if defined(__SANITIZE_ADDRESS__)
constexpr double kDefaultScale = 0.1;
#else
constexpr double kDefaultScale = 1.0;
#endif

double stressScale() {
    const char* s = std::getenv("IRIS_STRESS_SCALE");
    const double v = s ? std::atof(s) : 0.0;
    return v > 0 ? v : kDefaultScale;
}

constexpr double kPi = 3.14159265358979323846;

double cosDeg(double deg) { return std::cos(deg * kPi / 180.0); }

/// Grid thinned by the stress scale: keep every k-th entry (always keeping the ends).
std::vector<double> thin(const std::vector<double>& v) {
    const double s = stressScale();
    if (s >= 1.0) return v;
    const size_t step = std::max<size_t>(1, size_t(std::lround(1.0 / std::sqrt(s))));
    std::vector<double> out;
    for (size_t i = 0; i < v.size(); i += step) out.push_back(v[i]);
    if (out.back() != v.back()) out.push_back(v.back());
    return out;
}

std::string params(double deg, double n0, complexd film, double d, double lambda, complexd sub) {
    std::ostringstream os;
    os << std::setprecision(6) << "theta=" << deg << " n0=" << n0 << " film=" << film.real() << "+" << film.imag()
       << "i d=" << d << " lambda=" << lambda << " sub=" << sub.real() << "+" << sub.imag() << "i";
    return os.str();
}

const std::vector<double> kAngles = {0, 1e-3, 5, 15, 30, 40, 45, 50, 60, 70, 80, 85, 88, 89, 89.5, 89.9, 89.99};
const std::vector<double> kEtas = {1.0001, 1.001, 1.05, 1.2, 1.33, 1.5, 1.8, 2.2, 2.8, 3.4, 4.0};
const std::vector<double> kKs = {0, 1e-6, 1e-3, 0.1, 1, 10};
const std::vector<double> kThick = {0, 1e-3, 1, 10, 100, 500, 1e3, 1e4, 5e4, 1e5};
const std::vector<double> kLambdas = {360, 400, 450, 500, 550, 600, 650, 700, 760, 830};
const std::vector<complexd> kSubs = {{1.0, 0}, {1.0001, 0}, {1.5, 0}, {4.0, 0}, {0.15, 3.6}, {2.9, 0.6}, {1.0001, 10}};
const std::vector<double> kIncident = {1.0, 1.6};

TEST(FilmStackStress, DenseSingleFilmGrid) {
    double maxLosslessDefect = 0, maxAiryVsTmm = 0;
    std::string whereLossless, whereAiry;
    long n = 0;
    int failures = 0;
    std::string firstFailure;
    auto bad = [&](const std::string& m) {
        if (failures++ == 0) firstFailure = m;
    };
    const auto angles = thin(kAngles), etas = thin(kEtas), thick = thin(kThick), lambdas = thin(kLambdas);
    for (double deg : angles)
        for (double eta : etas)
            for (double k : kKs)
                for (double d : thick)
                    for (double lambda : lambdas)
                        for (const complexd& sub : kSubs)
                            for (double n0 : kIncident) {
                                const double c = cosDeg(deg);
                                const Layer film{complexd(eta, k), d};
                                const ThinFilmStackResult r[4] = {airySingleFilm(lambda, c, n0, film, sub),
                                                              thinFilmStackRT(lambda, c, n0, std::span(&film, 1), sub),
                                                              incoherentSingleFilm(lambda, c, n0, film, sub),
                                                              truncatedSingleFilm(lambda, c, n0, film, sub, 8)};
                                ++n;
                                for (int m = 0; m < 4; ++m) {
                                    for (double v : {r[m].Rs, r[m].Rp, r[m].Ts, r[m].Tp})
                                        if (!std::isfinite(v) || v < 0 || (m < 3 && v > 1))
                                            bad("method " + std::to_string(m) + " value " + std::to_string(v) + " at " +
                                                params(deg, n0, film.ior, d, lambda, sub));
                                    if (m < 3 && (r[m].Rs + r[m].Ts > 1 + 1e-9 || r[m].Rp + r[m].Tp > 1 + 1e-9))
                                        bad("method " + std::to_string(m) + " R + T > 1 at " +
                                            params(deg, n0, film.ior, d, lambda, sub));
                                }
                                // Lossless film and substrate: R + T = 1 (below and beyond the critical angle).
                                if (k == 0 && sub.imag() == 0) {
                                    for (int m = 0; m < 2; ++m) {
                                        const double e = std::max(std::abs(r[m].Rs + r[m].Ts - 1), std::abs(r[m].Rp + r[m].Tp - 1));
                                        if (e > maxLosslessDefect) {
                                            maxLosslessDefect = e;
                                            whereLossless = (m ? "TMM " : "Airy ") + params(deg, n0, film.ior, d, lambda, sub);
                                        }
                                    }
                                }
                                const double dA = std::max({std::abs(r[0].Rs - r[1].Rs), std::abs(r[0].Rp - r[1].Rp),
                                                            std::abs(r[0].Ts - r[1].Ts), std::abs(r[0].Tp - r[1].Tp)});
                                if (dA > maxAiryVsTmm) {
                                    maxAiryVsTmm = dA;
                                    whereAiry = params(deg, n0, film.ior, d, lambda, sub);
                                }
                            }
    std::cout << std::setprecision(3) << "FILM-STRESS | dense single-film grid | " << n << " points x 4 methods"
              << " | max |R+T-1| lossless " << maxLosslessDefect << " at " << whereLossless
              << " | max |Airy - TMM| " << maxAiryVsTmm << " at " << whereAiry << "\n";
    EXPECT_EQ(failures, 0) << failures << " invalid results; first: " << firstFailure;
    EXPECT_LT(maxLosslessDefect, 1e-9) << whereLossless;
    EXPECT_LT(maxAiryVsTmm, 1e-9) << whereAiry;
}

TEST(FilmStackStress, RandomFiftyLayerStacks) {
    std::mt19937_64 rng(20261122);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    auto logUniform = [&](double lo, double hi) { return lo * std::pow(hi / lo, U(rng)); };
    const int stacks = std::max(50, int(3000 * stressScale()));
    double maxLosslessDefect = 0;
    std::string whereLossless;
    int failures = 0;
    std::string firstFailure;
    std::vector<Layer> layers;
    for (int i = 0; i < stacks; ++i) {
        const bool lossless = i % 2 == 0;
        const int count = i % 5 == 0 ? 50 : 1 + int(U(rng) * 50);
        layers.clear();
        for (int j = 0; j < count; ++j) {
            const double eta = 1.0001 + 2.9999 * U(rng);
            const double k = lossless || U(rng) < 0.5 ? 0.0 : logUniform(1e-6, 10);
            const double pick = U(rng);
            const double d = pick < 0.1 ? 0.0 : pick < 0.2 ? 1e5 : logUniform(1e-3, 1e5);
            layers.push_back({complexd(eta, k), d});
        }
        const complexd sub = lossless ? complexd(1.0001 + 2.9999 * U(rng), 0) : complexd(0.1 + 3.9 * U(rng), 10 * U(rng));
        const double pickA = U(rng);
        const double deg = pickA < 0.1 ? 89.99 : pickA < 0.15 ? 0.0 : 89.99 * U(rng);
        const double lambda = i % 7 == 0 ? 360.0 : i % 7 == 1 ? 830.0 : 360 + 470 * U(rng);
        const double n0 = U(rng) < 0.3 ? 1.0 + 3.0 * U(rng) : 1.0;
        const ThinFilmStackResult r = thinFilmStackRT(lambda, cosDeg(deg), n0, layers, sub);
        std::ostringstream where;
        where << "stack " << i << " (" << count << " layers) theta=" << deg << " lambda=" << lambda << " n0=" << n0;
        for (double v : {r.Rs, r.Rp, r.Ts, r.Tp})
            if (!std::isfinite(v) || v < 0 || v > 1)
                if (failures++ == 0) firstFailure = where.str() + " value " + std::to_string(v);
        if (r.Rs + r.Ts > 1 + 1e-9 || r.Rp + r.Tp > 1 + 1e-9)
            if (failures++ == 0) firstFailure = where.str() + " R + T > 1";
        if (lossless) {
            const double e = std::max(std::abs(r.Rs + r.Ts - 1), std::abs(r.Rp + r.Tp - 1));
            if (e > maxLosslessDefect) {
                maxLosslessDefect = e;
                whereLossless = where.str();
            }
        }
    }
    std::cout << std::setprecision(3) << "FILM-STRESS | random stacks up to 50 layers | " << stacks
              << " stacks (seed 20261122) | max |R+T-1| lossless " << maxLosslessDefect << " at " << whereLossless << "\n";
    EXPECT_EQ(failures, 0) << firstFailure;
    EXPECT_LT(maxLosslessDefect, 1e-8) << whereLossless;
}

// ---- float re-evaluation of the Airy formula --------------------------------------------------

template <typename T>
struct AiryResult {
    T Rs, Rp, Ts, Tp;
};

/// Single-film Airy sum in precision T, written directly from the formulas (Born & Wolf
/// 7.6(14)–(15)) with tilted admittances y_s = q, y_p = q/ñ² (Macleod §2.2), q = sqrt(ñ² − s²)
/// on the decaying branch, r_ij = (y_i − y_j)/(y_i + y_j), t_ij = 2y_i/(y_i + y_j),
/// T = Re(y2)/y0 |t|². An independent copy (not the library code), used at T = float and double.
/// Stable = false forms q² = ñ² − s² with s = n0 sinθ (the textbook form); Stable = true forms
/// q² = (ñ − n0)(ñ + n0) + q0², q0 = n0 cosθ, which avoids the cancellation of ñ² − s² near grazing
/// incidence when ñ ≈ n0 (in float, 1 − sin²89.99° = 3e-8 is below the rounding of sin²θ).
template <typename T, bool Stable>
AiryResult<T> airyT(T lambda, T cosI, T n0, std::complex<T> n1, T d, std::complex<T> n2) {
    using C = std::complex<T>;
    const T s = n0 * std::sqrt(std::max(T(0), T(1) - cosI * cosI));
    const T q0r = n0 * cosI;
    auto q = [&](C n) {
        C r = Stable ? std::sqrt((n - C(n0, T(0))) * (n + C(n0, T(0))) + C(q0r * q0r, T(0)))
                     : std::sqrt(n * n - C(s * s, T(0)));
        if (r.imag() < 0 || (r.imag() == 0 && r.real() < 0)) r = -r;
        return r;
    };
    const C q0(q0r, T(0)), q1 = q(n1), q2 = q(n2);
    const C delta = T(2 * kPi) / lambda * d * q1;
    const C E = std::exp(C(T(0), T(2)) * delta), half = std::exp(C(T(0), T(1)) * delta);
    AiryResult<T> out{};
    for (int pol = 0; pol < 2; ++pol) {
        const C y0 = pol == 0 ? q0 : q0 / C(n0 * n0, T(0));
        const C y1 = pol == 0 ? q1 : q1 / (n1 * n1);
        const C y2 = pol == 0 ? q2 : q2 / (n2 * n2);
        const C r01 = (y0 - y1) / (y0 + y1), r12 = (y1 - y2) / (y1 + y2);
        const C t01 = T(2) * y0 / (y0 + y1), t12 = T(2) * y1 / (y1 + y2);
        const C den = T(1) + r01 * r12 * E;
        const T R = std::norm((r01 + r12 * E) / den);
        const T Tr = y2.real() / y0.real() * std::norm(t01 * t12 * half / den);
        (pol == 0 ? out.Rs : out.Rp) = R;
        (pol == 0 ? out.Ts : out.Tp) = Tr;
    }
    return out;
}

TEST(FilmStackStress, FloatAiryAgainstDouble) {
    // Thickness ranges reported separately (the float phase error grows with d).
    const std::vector<std::pair<double, double>> ranges = {{0, 1e3}, {1e3, 1e4}, {1e4, 1e5}};
    // [variant][range]: variant 0 = textbook q² = ñ² − s², 1 = stable q² = (ñ − n0)(ñ + n0) + q0².
    std::vector<double> maxAbsR[2], maxRelR[2], maxAbsT[2];
    std::vector<std::string> whereAbs[2];
    for (int v = 0; v < 2; ++v) {
        maxAbsR[v].assign(ranges.size(), 0);
        maxRelR[v].assign(ranges.size(), 0);
        maxAbsT[v].assign(ranges.size(), 0);
        whereAbs[v].assign(ranges.size(), "");
    }
    double maxTemplateVsLibrary = 0;
    std::string whereTemplate;
    long n = 0;
    const auto angles = thin(kAngles), etas = thin(kEtas), thick = thin(kThick), lambdas = thin(kLambdas);
    for (double deg : angles)
        for (double eta : etas)
            for (double k : kKs)
                for (double d : thick)
                    for (double lambda : lambdas)
                        for (const complexd& sub : kSubs) {
                            const double n0 = 1.0, c = cosDeg(deg);
                            const complexd film(eta, k);
                            const ThinFilmStackResult lib = airySingleFilm(lambda, c, n0, {film, d}, sub);
                            const AiryResult<double> dbl = airyT<double, false>(lambda, c, n0, film, d, sub);
                            const AiryResult<double> dblStable = airyT<double, true>(lambda, c, n0, film, d, sub);
                            const std::complex<float> filmF{float(eta), float(k)}, subF{float(sub.real()), float(sub.imag())};
                            const AiryResult<float> flts[2] = {
                                airyT<float, false>(float(lambda), float(c), float(n0), filmF, float(d), subF),
                                airyT<float, true>(float(lambda), float(c), float(n0), filmF, float(d), subF)};
                            ++n;
                            const double dt = std::max({std::abs(dbl.Rs - lib.Rs), std::abs(dbl.Rp - lib.Rp),
                                                        std::abs(dbl.Ts - lib.Ts), std::abs(dbl.Tp - lib.Tp),
                                                        std::abs(dblStable.Rs - lib.Rs), std::abs(dblStable.Rp - lib.Rp),
                                                        std::abs(dblStable.Ts - lib.Ts), std::abs(dblStable.Tp - lib.Tp)});
                            if (!(dt <= maxTemplateVsLibrary)) {
                                maxTemplateVsLibrary = dt;
                                whereTemplate = params(deg, n0, film, d, lambda, sub);
                            }
                            size_t b = 0;
                            while (b + 1 < ranges.size() && d > ranges[b].second) ++b;
                            const double R = lib.R();
                            for (int v = 0; v < 2; ++v) {
                                const AiryResult<float>& flt = flts[v];
                                ASSERT_TRUE(std::isfinite(flt.Rs) && std::isfinite(flt.Rp) && std::isfinite(flt.Ts) &&
                                            std::isfinite(flt.Tp))
                                    << params(deg, n0, film, d, lambda, sub);
                                const double Rf = 0.5 * (double(flt.Rs) + double(flt.Rp));
                                const double Tf = 0.5 * (double(flt.Ts) + double(flt.Tp));
                                const double aR = std::abs(Rf - R);
                                if (aR > maxAbsR[v][b]) {
                                    maxAbsR[v][b] = aR;
                                    whereAbs[v][b] = params(deg, n0, film, d, lambda, sub);
                                }
                                if (R > 1e-3) maxRelR[v][b] = std::max(maxRelR[v][b], aR / R);
                                maxAbsT[v][b] = std::max(maxAbsT[v][b], std::abs(Tf - lib.T()));
                            }
                        }
    std::cout << std::setprecision(3) << "FILM-STRESS | float Airy vs double | " << n << " points | template(double) vs "
              << "library max diff " << maxTemplateVsLibrary << " at " << whereTemplate << "\n";
    for (int v = 0; v < 2; ++v)
        for (size_t b = 0; b < ranges.size(); ++b)
            std::cout << std::setprecision(3) << "FILM-STRESS | float Airy vs double, "
                      << (v ? "stable q^2 = (n-n0)(n+n0)+q0^2" : "textbook q^2 = n^2-s^2") << " | d in ("
                      << ranges[b].first << ", " << ranges[b].second << "] nm | max |dR| " << maxAbsR[v][b]
                      << " | max |dR|/R (R > 1e-3) " << maxRelR[v][b] << " | max |dT| " << maxAbsT[v][b]
                      << " | worst at " << whereAbs[v][b] << "\n";
    // The template must be the same formula as the library (else the float numbers mean nothing).
    EXPECT_LT(maxTemplateVsLibrary, 1e-9) << whereTemplate;
    // Float error model for the stable form: the interface coefficients carry a few ε_f (6e-8)
    // relative error, amplified near grazing incidence where r01 → −1 and R − 1 ∝ y0 = n0 cosθ
    // (cosθ = 1.7e-4 at 89.99°): ≲ 1e-3 for thin films. The phase 2δ = 4π ñ d cosθ1/λ
    // (≤ 1.4e4 rad at d = 1e5 nm) is rounded to ≈ ε_f·2δ ≈ 1e-3 rad and multiplied by dR/d(2δ),
    // which grows with the fringe finesse: a few 1e-3 at d = 1e4 nm, ≲ 2e-2 at 1e5 nm.
    EXPECT_LT(maxAbsR[1][0], 1e-3) << whereAbs[1][0];
    EXPECT_LT(maxAbsR[1][1], 5e-3) << whereAbs[1][1];
    EXPECT_LT(maxAbsR[1][2], 2e-2) << whereAbs[1][2];
    // The textbook q² = ñ² − s² is ill-conditioned at grazing incidence when ñ ≈ n0: in float it
    // is off by far more (measured 0.14 in R for thin films) — the reason a float path must use
    // the stable form.
    EXPECT_GT(maxAbsR[0][0], 10 * maxAbsR[1][0]);
}

TEST(FilmStackStress, FloatPhaseTerm) {
    // Φ = π η d/λ (cosθti + cosθto), the granier/proposed interference phase (thesis 000 eq. 2.28,
    // 3.20) evaluated in float as those materials do; the float error of cos(2Φ) grows like
    // ε_f · 2Φ.
    double maxErr1e3 = 0, maxErr1e5 = 0;
    for (double d : {10.0, 100.0, 500.0, 1e3, 5e3, 1e4, 5e4, 1e5})
        for (double eta : {1.0001, 1.5, 2.5, 4.0})
            for (double lambda : {360.0, 445.0, 525.0, 645.0, 830.0})
                for (double ct : {1.0, 0.9, 0.5, 0.1, 1e-3}) {
                    const float phaseF = 3.14159265f * float(eta) * float(d) / float(lambda) * (float(ct) + float(ct));
                    const double phaseD = kPi * eta * d / lambda * (ct + ct);
                    const double e = std::abs(double(std::cos(2.0f * phaseF)) - std::cos(2.0 * phaseD));
                    (d <= 1e3 ? maxErr1e3 : maxErr1e5) = std::max(d <= 1e3 ? maxErr1e3 : maxErr1e5, e);
                }
    std::cout << std::setprecision(3) << "FILM-STRESS | float phase term cos(2 Phi) | max |error| d <= 1e3 nm "
              << maxErr1e3 << " | 1e3 < d <= 1e5 nm " << maxErr1e5 << "\n";
    // 2Φ ≤ 2π·4·1e5/360·2 ≈ 1.4e4 rad: float rounding of the product ≈ 1.4e4 · 6e-8 ≈ 1e-3.
    EXPECT_LT(maxErr1e3, 1e-4);
    EXPECT_LT(maxErr1e5, 1e-2);
}

}  // namespace
