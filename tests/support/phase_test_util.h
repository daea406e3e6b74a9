// Shared helpers of the phase-function tests (tests/materials/test_phase_*.cpp): a phase function
// seen through the BSDF interface, so that the χ² harness of bsdf_test_util.h tests its sampling,
// and ∫ p dωi with its standard error.
#pragma once

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <memory>
#include <string>

#include "core/rng.h"
#include "core/xml/xml_parser.h"
#include "core/sampling.h"
#include "media/phase/phase_function.h"
#include "tests/support/bsdf_test_util.h"

namespace iris::test {

/// A phase function at the world point x seen through the BSDF interface (its local frame is the
/// world frame): f·|cos θi| / pdf = p / pdf, so eval returns p / |cos θi| (which the χ² harness
/// never looks at) and pdf the phase function's pdf. With a `sampler`, directions come from that
/// other phase function while eval and pdf stay this one's: χ² must then reject a mismatch.
class PhaseAsBSDF final : public BSDF {
public:
    explicit PhaseAsBSDF(const PhaseFunction& p, const vec3& x = vec3(0.0f), const PhaseFunction* sampler = nullptr)
        : p_(p), sampler_(sampler ? *sampler : p), x_(x) {}
    SampledSpectrum eval(const vec3& wo, const vec3& wi, TransportMode) const override {
        return SampledSpectrum(1, p_.eval(x_, wo, wi) / std::max(std::abs(wi.z), 1e-6f));
    }
    float pdf(const vec3& wo, const vec3& wi, TransportMode) const override { return p_.pdf(x_, wo, wi); }
    std::optional<BSDFSample> sample(const vec3& wo, float, const vec2& u, TransportMode) const override {
        const auto s = sampler_.sample(x_, wo, u);
        if (!s) return std::nullopt;
        const bool own = &sampler_ == &p_;
        BSDFSample b;
        b.wi = s->wi;
        b.pdf = own ? s->pdf : p_.pdf(x_, wo, s->wi);
        b.f = SampledSpectrum(1, (own ? s->p : p_.eval(x_, wo, s->wi)) / std::max(std::abs(s->wi.z), 1e-6f));
        b.flags = kBSDFGlossy | kBSDFReflection | kBSDFTransmission;
        return b;
    }
    uint32_t flags() const override { return kBSDFGlossy | kBSDFReflection | kBSDFTransmission; }

private:
    const PhaseFunction &p_, &sampler_;
    vec3 x_;
};

/// A phase function of `type` created through the registry from parameters.
inline std::shared_ptr<PhaseFunction> makePhase(const std::string& type, std::initializer_list<Param> params = {}) {
    const SourceLocation loc{"<test>", 1};
    Properties p("phase", type, loc);
    for (const Param& kv : params) p.set(kv.first, kv.second, loc);
    return PhaseFunctionRegistry::instance().create(p);
}

/// ∫ p(x, wo, wi) dωi by uniform sphere sampling (mean and standard error of the estimate), and
/// the mean under p of cos θ = −wo·wi.
struct PhaseIntegral {
    double mean = 0, stdError = 0, meanCos = 0;
};

inline PhaseIntegral integratePhase(const PhaseFunction& p, const vec3& x, const vec3& wo, int n = 400000, uint64_t seed = 5) {
    Pcg32 rng(seed, 7);
    double sum = 0, sum2 = 0, mu = 0;
    for (int i = 0; i < n; ++i) {
        const vec3 wi = sampleUniformSphere(vec2(rng.uniform(), rng.uniform()));
        const double v = p.eval(x, wo, wi) / uniformSpherePdf();
        sum += v;
        sum2 += v * v;
        mu += v * -glm::dot(wo, wi);
    }
    const double mean = sum / n;
    return {mean, std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n), mu / n};
}

/// The checks every phase function passes at the point x seen from wo: ∫p = 1 within 5 standard
/// errors, χ² of its samples against its pdf (Šidák-corrected for `numTests`), and samples whose
/// value and pdf are eval() and pdf() at their direction (relative tolerance `tol`).
inline void expectNormalisedAndSampledByItsPdf(const PhaseFunction& p, const vec3& x, const vec3& wo, int numTests, float tol = 1e-5f) {
    const PhaseIntegral r = integratePhase(p, x, wo);
    EXPECT_LT(r.stdError, 0.01);  // the estimate can tell a wrong normalisation
    EXPECT_NEAR(r.mean, 1.0, 5 * r.stdError);
    Chi2Options opt;
    opt.numTests = numTests;
    const Chi2Result c = chi2Test(PhaseAsBSDF(p, x), wo, opt);
    EXPECT_TRUE(c.passed) << c.message;
    EXPECT_NEAR(c.pdfMass, 1.0, 2e-3);
    Pcg32 rng(7, 1);
    for (int i = 0; i < 1000; ++i) {
        const auto s = p.sample(x, wo, vec2(rng.uniform(), rng.uniform()));
        ASSERT_TRUE(s);
        EXPECT_NEAR(glm::length(s->wi), 1.0f, 1e-5f);
        EXPECT_NEAR(s->p, p.eval(x, wo, s->wi), tol * s->p);
        EXPECT_NEAR(s->pdf, p.pdf(x, wo, s->wi), tol * s->pdf);
    }
}

/// A phase function from its XML element (`<phase type="...">...</phase>`, written from line 2 of a
/// scene string, so messages name "<string>:2" for its first line); nested volumes' files are
/// resolved against the current folder.
inline std::shared_ptr<PhaseFunction> phaseFromXml(const std::string& xml) {
    const ParsedScene parsed = parseSceneString("<scene version=\"3.0.0\">\n" + xml + "\n</scene>\n", ".");
    return PhaseFunctionRegistry::instance().create(*parsed.objects.at(0));
}

}  // namespace iris::test
