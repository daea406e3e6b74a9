// Numerical stress test of every registered material (issue 7; docs/numerics.md).
//
// For every name in MaterialRegistry (so new materials are covered automatically; a material
// without an entry in tests/support/stress_configs.cpp fails here; probes registered by tests, whose names
// contain "test", are skipped), every stress configuration and every
// wavelength set (RGB mode; N = 1 at 360 and at 830 nm; N = 4 visible-importance; N = 32 from
// 360 and up to 830 nm):
//   * shadingFrame() at random uvs is finite and orthonormal;
//   * random queries — directions over the whole sphere with a share of special ones (exactly
//     normal, cosθ = cos 89.99°, exactly on the horizon, 1e-7 from the normal, below the horizon),
//     random samples with a share of 0 and 1−ε — in both transport modes:
//       eval finite and ≥ 0; pdf finite and ≥ 0; sample(): wi finite and unit length, pdf > 0,
//       f and the weight f·|cosθi|/pdf finite and ≥ 0; for non-specular samples f and pdf equal
//       eval(wo, wi) and pdf(wo, wi) to 1e-2 (maxima printed as "STRESS-CONSISTENCY");
//   * directional albedo (mean of sample() weights) for several wo, both above and below the
//     horizon: energy-conserving materials must stay ≤ 1 + 5σ + 2e-3 in importance transport
//     (the adjoint: light arriving from wo, so the radiance-mode 1/η² factor of refraction does
//     not count) and also in radiance transport for reflection-only BSDFs. Materials that do not
//     conserve energy by design only have to stay below a generous bound (mean − 5σ < bound); their maximum excess
//     is printed ("STRESS-ENERGY" lines) and copied into docs/numerics.md.
// Counts scale with the environment variable IRIS_STRESS_SCALE (default 1; 0.1 under ASan).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <sstream>

#include "core/registry.h"
#include "core/rng.h"
#include "materials/material.h"
#include "tests/support/stress_configs.h"

using namespace iris;

namespace {

#if defined(__SANITIZE_ADDRESS__)
constexpr double kDefaultScale = 0.1;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr double kDefaultScale = 0.1;
#else
constexpr double kDefaultScale = 1.0;
#endif
#else
constexpr double kDefaultScale = 1.0;
#endif

double stressScale() {
    const char* s = std::getenv("IRIS_STRESS_SCALE");
    if (!s) return kDefaultScale;
    const double v = std::atof(s);
    return v > 0 ? v : kDefaultScale;
}

int scaled(int n) { return std::max(16, int(std::lround(n * stressScale()))); }

constexpr float kOneMinusEps = 0x1.fffffep-1f;
const float kCos8999 = std::cos(89.99f * 3.14159265358979f / 180.0f);  // 1.745e-4

uint64_t fnv1a(const std::string& s, uint64_t salt) {
    uint64_t h = 1469598103934665603ull ^ salt;
    for (unsigned char c : s) h = (h ^ c) * 1099511628211ull;
    return h;
}

struct WavelengthSet {
    std::string label;
    SampledWavelengths wl;
};

std::vector<WavelengthSet> wavelengthSets() {
    return {
        {"RGB", SampledWavelengths::rgb(defaultChannelWavelengths())},
        {"N=1@360", SampledWavelengths::sampleUniform(0.0f, 1)},
        {"N=1@830", SampledWavelengths::sampleUniform(kOneMinusEps, 1)},
        {"N=4", SampledWavelengths::sampleVisible(0.37f, 4)},
        {"N=32@360", SampledWavelengths::sampleUniform(0.0f, 32)},
        {"N=32@830", SampledWavelengths::sampleUniform(kOneMinusEps, 32)},
    };
}

vec3 fromCosPhi(float c, float phi) {
    const float s = std::sqrt(std::max(0.0f, 1.0f - c * c));
    return vec3(s * std::cos(phi), s * std::sin(phi), c);
}

/// A direction: 55% uniform on the sphere, the rest special cases (signs random).
vec3 stressDirection(Sampler& rng) {
    const float k = rng.get1D();
    const float phi = 6.2831853f * rng.get1D();
    const float sign = rng.get1D() < 0.5f ? 1.0f : -1.0f;
    if (k < 0.55f) return fromCosPhi(2.0f * rng.get1D() - 1.0f, phi);
    if (k < 0.70f) return fromCosPhi(sign * kCos8999, phi);      // 89.99°
    if (k < 0.78f) return vec3(0.0f, 0.0f, sign);                 // exactly normal
    if (k < 0.84f) return fromCosPhi(0.0f, phi);                  // exactly on the horizon
    if (k < 0.90f) return fromCosPhi(sign * (1.0f - 1e-7f), phi); // almost normal
    return fromCosPhi(sign * rng.get1D() * 0.01f, phi);          // grazing band
}

float stressU(Sampler& rng) {
    const float k = rng.get1D();
    if (k < 0.05f) return 0.0f;
    if (k < 0.10f) return kOneMinusEps;
    return rng.get1D();
}

bool finiteVec(const vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

std::string str(const vec3& v) {
    std::ostringstream os;
    os << std::setprecision(9) << "(" << v.x << ", " << v.y << ", " << v.z << ")";
    return os.str();
}

std::string str(const SampledSpectrum& s) {
    std::ostringstream os;
    os << std::setprecision(7) << "[";
    for (int i = 0; i < s.size(); ++i) os << (i ? " " : "") << s[i];
    return os.str() + "]";
}

bool badSpectrum(const SampledSpectrum& s) { return s.hasNonFinite() || s.hasNegative(); }

/// Failure collector: counts everything, keeps the first few messages.
struct Failures {
    int count = 0;
    std::vector<std::string> first;
    void add(const std::string& m) {
        if (count++ < 12) first.push_back(m);
    }
    std::string text() const {
        std::string t;
        for (const auto& m : first) t += "\n  " + m;
        if (count > int(first.size())) t += "\n  ... (" + std::to_string(count - int(first.size())) + " more)";
        return t;
    }
};

struct AlbedoExtreme {
    double mean = -1, sigma = 0;
    std::string where;
};

class MaterialStress : public ::testing::TestWithParam<std::string> {};

TEST_P(MaterialStress, FiniteNonNegativeAndBoundedAlbedo) {
    const std::string name = GetParam();
    const stress::MaterialStress cfg = stress::stressConfigsFor(name);
    ASSERT_TRUE(cfg.known) << "material '" << name
                           << "' has no stress configuration: add an entry (extreme parameters, energy "
                              "expectation) to tests/support/stress_configs.cpp";
    ASSERT_FALSE(cfg.cases.empty()) << name;

    const int queriesPerSet = scaled(2500);
    const int albedoSamples = scaled(4000);
    const std::vector<WavelengthSet> sets = wavelengthSets();
    // Albedo: wo above and below the horizon (cosθo), and these wavelength sets.
    const float kCos899 = std::cos(89.9f * 3.14159265358979f / 180.0f);
    const float albedoCos[] = {1.0f, 0.5f, 0.05f, kCos899, kCos8999, -0.5f, -kCos8999};
    const int albedoSets[] = {0, 3, 5};

    Failures fail;
    AlbedoExtreme worst, worstPdf{0, 0, ""}, worstF{0, 0, ""};
    std::vector<AlbedoExtreme> knownWorst(cfg.cases.size());
    long long queries = 0, albedoQueries = 0;

    for (size_t ci = 0; ci < cfg.cases.size(); ++ci) {
        const stress::StressCase& sc = cfg.cases[ci];
        std::shared_ptr<Material> mat;
        try {
            mat = MaterialRegistry::instance().create(*sc.props);
        } catch (const Error& e) {
            fail.add("[" + sc.label + "] creation threw: " + e.what());
            continue;
        }
        for (size_t si = 0; si < sets.size(); ++si) {
            const std::string where0 = "[" + sc.label + " | " + sets[si].label + "]";
            Sampler rng(fnv1a(name, ci * 131 + si));
            Arena arena;
            const int shadingPoints = 4;
            for (int spi = 0; spi < shadingPoints; ++spi) {
                arena.reset();
                ShadingPoint sp;
                sp.tex.uv = rng.get2D() * 4.0f - 2.0f;
                sp.tex.p = vec3(sp.tex.uv, 0.0f);
                const Frame fr = mat->shadingFrame(sp);
                const float orth = std::max({std::abs(glm::dot(fr.s, fr.t)), std::abs(glm::dot(fr.s, fr.n)),
                                             std::abs(glm::dot(fr.t, fr.n)), std::abs(glm::length(fr.n) - 1.0f),
                                             std::abs(glm::length(fr.s) - 1.0f), std::abs(glm::length(fr.t) - 1.0f)});
                if (!finiteVec(fr.s) || !finiteVec(fr.t) || !finiteVec(fr.n) || !(orth < 1e-4f))
                    fail.add(where0 + " shadingFrame not orthonormal: n=" + str(fr.n) + " s=" + str(fr.s));
                SampledWavelengths wl = sets[si].wl;
                const BSDF* bsdf = mat->getBSDF(sp, wl, arena);
                if (!bsdf) continue;
                for (int q = 0; q < queriesPerSet / shadingPoints; ++q, ++queries) {
                    const TransportMode mode = (q & 1) ? TransportMode::Importance : TransportMode::Radiance;
                    const vec3 wo = stressDirection(rng), wi = stressDirection(rng);
                    const std::string where = where0 + (mode == TransportMode::Radiance ? " rad" : " imp") +
                                              " wo=" + str(wo);
                    const SampledSpectrum f = bsdf->eval(wo, wi, mode);
                    if (badSpectrum(f)) fail.add(where + " wi=" + str(wi) + " eval=" + str(f));
                    const float pdf = bsdf->pdf(wo, wi, mode);
                    if (!std::isfinite(pdf) || pdf < 0)
                        fail.add(where + " wi=" + str(wi) + " pdf=" + std::to_string(pdf));
                    const float uc = stressU(rng);
                    const vec2 u(stressU(rng), stressU(rng));
                    const auto s = bsdf->sample(wo, uc, u, mode);
                    if (!s) continue;
                    const std::string sw = where + " uc=" + std::to_string(uc) + " u=(" + std::to_string(u.x) + ", " +
                                           std::to_string(u.y) + ") -> wi=" + str(s->wi);
                    if (!finiteVec(s->wi) || !(std::abs(glm::length(s->wi) - 1.0f) < 1e-3f))
                        fail.add(sw + " sampled wi not a finite unit vector");
                    if (!std::isfinite(s->pdf) || !(s->pdf > 0)) fail.add(sw + " sampled pdf=" + std::to_string(s->pdf));
                    if (badSpectrum(s->f)) fail.add(sw + " sampled f=" + str(s->f));
                    const SampledSpectrum w = s->weight();
                    if (badSpectrum(w)) fail.add(sw + " weight=" + str(w));
                    // Consistency with eval/pdf for non-specular samples: relative difference ≤ 1e-2
                    // (values below 1e-6 ignored), except inside a known defect's angular range.
                    if (!s->isSpecular() && s->pdf > 0) {
                        const bool known = (sc.knownAlbedoLimit > 0 && std::abs(wo.z) < sc.knownBelowCos) ||
                                           !cfg.consistencyKnownIssue.empty();
                        const float pq = bsdf->pdf(wo, s->wi, mode);
                        const float rel = std::abs(pq - s->pdf) / std::max(pq, s->pdf);
                        if (rel > worstPdf.mean) worstPdf = {rel, 0, sw};
                        if (!known && rel > 1e-2f && std::max(pq, s->pdf) > 1e-6f)
                            fail.add(sw + " sample.pdf=" + std::to_string(s->pdf) + " but pdf(wo, wi)=" + std::to_string(pq));
                        const SampledSpectrum fq = bsdf->eval(wo, s->wi, mode);
                        for (int k = 0; k < fq.size(); ++k) {
                            const float m = std::max(fq[k], s->f[k]);
                            const float r = m > 0 ? std::abs(fq[k] - s->f[k]) / m : 0.0f;
                            if (r > worstF.mean) worstF = {r, 0, sw};
                            if (!known && r > 1e-2f && m > 1e-6f) {
                                fail.add(sw + " sample.f=" + str(s->f) + " but eval(wo, wi)=" + str(fq));
                                break;
                            }
                        }
                    }
                }
            }
        }

        // Directional albedo.
        for (int si : albedoSets) {
            for (int wi = 0; wi < int(std::size(albedoCos)); ++wi) {
                const float c = albedoCos[wi];
                for (TransportMode mode : {TransportMode::Importance, TransportMode::Radiance}) {
                    Sampler rng(fnv1a(name, 7777 + ci * 131 + si * 17 + wi));
                    Arena arena;
                    ShadingPoint sp;
                    SampledWavelengths wl = sets[si].wl;
                    const BSDF* bsdf = mat->getBSDF(sp, wl, arena);
                    if (!bsdf) continue;
                    const bool transmissive = bsdf->flags() & kBSDFTransmission;
                    if (mode == TransportMode::Radiance && transmissive) continue;
                    const vec3 wo = fromCosPhi(c, 0.7f);
                    std::vector<double> s1(wl.size(), 0.0), s2(wl.size(), 0.0);
                    for (int i = 0; i < albedoSamples; ++i, ++albedoQueries) {
                        const float uc = rng.get1D();
                        const auto smp = bsdf->sample(wo, uc, rng.get2D(), mode);
                        if (!smp || !(smp->pdf > 0)) continue;
                        const SampledSpectrum w = smp->weight();
                        for (int k = 0; k < w.size(); ++k) {
                            const double v = std::isfinite(w[k]) ? w[k] : 1e30;
                            s1[k] += v;
                            s2[k] += v * v;
                        }
                    }
                    for (int k = 0; k < wl.size(); ++k) {
                        const double n = albedoSamples, mean = s1[k] / n;
                        const double var = std::max(0.0, s2[k] / n - mean * mean);
                        const double sigma = std::sqrt(var / (n - 1));
                        std::ostringstream where;
                        where << "[" << sc.label << " | " << sets[si].label << " | "
                              << (mode == TransportMode::Radiance ? "rad" : "imp") << "] cos(theta_o)=" << c
                              << " channel " << k << " (" << wl.lambda(k) << " nm)";
                        const bool known = sc.knownAlbedoLimit > 0 && std::abs(c) < sc.knownBelowCos;
                        if (known) {
                            if (mean > knownWorst[ci].mean) knownWorst[ci] = {mean, sigma, where.str()};
                            // The same variance-derived tolerance as the bounds below: the adjoint
                            // estimates near grazing angles are heavy-tailed (5.8 +- 3.4 at the
                            // sample counts of the ASan run, IRIS_STRESS_SCALE=0.1).
                            if (!(mean - 5.0 * sigma <= sc.knownAlbedoLimit)) {
                                std::ostringstream m;
                                m << where.str() << " albedo " << mean << " +- " << sigma
                                  << " exceeds even the limit of the known defect " << sc.knownAlbedoLimit << " ("
                                  << sc.knownIssue << ")";
                                fail.add(m.str());
                            }
                            continue;
                        }
                        if (mean > worst.mean) worst = {mean, sigma, where.str()};
                        if (cfg.conservesEnergy) {
                            if (!(mean <= 1.0 + 5.0 * sigma + 2e-3)) {
                                std::ostringstream m;
                                m << where.str() << " albedo " << mean << " +- " << sigma << " > 1";
                                fail.add(m.str());
                            }
                        } else if (!(mean - 5.0 * sigma < cfg.generousBound)) {
                            std::ostringstream m;
                            m << where.str() << " albedo " << mean << " +- " << sigma << " exceeds the generous bound "
                              << cfg.generousBound;
                            fail.add(m.str());
                        }
                    }
                }
            }
        }
    }

    std::cout << std::setprecision(4) << "STRESS-ENERGY | " << name << " | "
              << (cfg.conservesEnergy ? "conserving" : "not conserving") << " | max albedo " << worst.mean << " +- "
              << worst.sigma << " | excess " << std::max(0.0, worst.mean - 1.0) << " | at " << worst.where << " | "
              << queries << " queries, " << albedoQueries << " albedo samples"
              << (cfg.note.empty() ? "" : " | " + cfg.note) << "\n";
    std::cout << std::setprecision(3) << "STRESS-CONSISTENCY | " << name << " | max rel |pdf(wo,wi) - sample.pdf| "
              << worstPdf.mean << (worstPdf.where.empty() ? "" : " at " + worstPdf.where)
              << " | max rel |eval - sample.f| " << worstF.mean << (worstF.where.empty() ? "" : " at " + worstF.where)
              << (cfg.consistencyKnownIssue.empty() ? "" : " | known: " + cfg.consistencyKnownIssue) << "\n";
    for (size_t ci = 0; ci < cfg.cases.size(); ++ci)
        if (knownWorst[ci].mean >= 0)
            std::cout << std::setprecision(4) << "STRESS-KNOWN | " << name << " | max albedo " << knownWorst[ci].mean
                      << " +- " << knownWorst[ci].sigma << " (limit " << cfg.cases[ci].knownAlbedoLimit << ") | at "
                      << knownWorst[ci].where << " | " << cfg.cases[ci].knownIssue << "\n";
    EXPECT_EQ(fail.count, 0) << name << ": " << fail.count << " problems" << fail.text();
}

/// Every registered material except probes that tests register for themselves (names containing
/// "test", e.g. the scene loader's "loader_test_probe").
std::vector<std::string> materialsToStress() {
    std::vector<std::string> names;
    for (const std::string& n : MaterialRegistry::instance().names())
        if (n.find("test") == std::string::npos) names.push_back(n);
    return names;
}

INSTANTIATE_TEST_SUITE_P(Registered, MaterialStress, ::testing::ValuesIn(materialsToStress()),
                         [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

}  // namespace
