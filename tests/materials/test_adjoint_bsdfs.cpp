// Adjoint transport through every registered material (issue 35): light tracing and BDPT evaluate
// and sample BSDFs with TransportMode::Importance, which must be the adjoint of the radiance BSDF,
//     f*(wo, wi) = f(wi, wo)                                    (Veach 1997 eq. 3.21 and §5.2),
// for reflection and for refraction: the radiance BSDF of a refraction carries the 1/η² of
// radiance compression, its adjoint does not (Veach eq. 5.14: f(wo, wi)/η_o² = f(wi, wo)/η_i²).
// Checked on every stress configuration of every material (tests/support/stress_configs.cpp, so a
// new material is covered and one without configurations fails there), at random direction pairs
// over the whole sphere in RGB mode and with 4 spectral wavelengths. The sampling side of the
// importance mode (sample() against pdf() and eval()) is covered by MaterialStress and the
// chi-square tests of AdjointSampling below. The test can fail: an asymmetric probe BSDF that
// ignores the mode is caught.
#include <gtest/gtest.h>

#include <sstream>

#include "core/registry.h"
#include "core/rng.h"
#include "materials/material.h"
#include "tests/support/bsdf_test_util.h"
#include "tests/support/stress_configs.h"

using namespace iris;

namespace {

vec3 randomDirection(Sampler& rng) {
    // Away from the horizon (|cos θ| ≥ 0.05): grazing float noise is MaterialStress's subject.
    for (;;) {
        const vec2 u = rng.get2D();
        const float z = 1.0f - 2.0f * u.x, r = std::sqrt(std::max(0.0f, 1.0f - z * z)), phi = 6.2831853f * u.y;
        if (std::abs(z) >= 0.05f) return vec3(r * std::cos(phi), r * std::sin(phi), z);
    }
}

struct AdjointError {
    float worst = 0;     // max relative difference |f*(wo,wi) − f(wi,wo)| / max(·, floor)
    float offShare = 0;  // share of the pairs more than 1e-3 apart
    std::string where;
};

/// The relative differences between eval(wo, wi, Importance) and eval(wi, wo, Radiance) over
/// `pairs` random direction pairs, values below `floor` counting as `floor`. Float rounding near a
/// grazing microfacet (a dot product of 0.006 at η = 4) reaches a few per cent at rare pairs; a
/// wrong adjoint differs at most pairs or by far more.
AdjointError adjointError(const BSDF& bsdf, uint64_t seed, int pairs = 400, float floor = 1e-5f) {
    Sampler rng(seed);
    AdjointError e;
    int off = 0;
    for (int i = 0; i < pairs; ++i) {
        const vec3 wo = randomDirection(rng), wi = randomDirection(rng);
        const SampledSpectrum fi = bsdf.eval(wo, wi, TransportMode::Importance);
        const SampledSpectrum fr = bsdf.eval(wi, wo, TransportMode::Radiance);
        float pairWorst = 0;
        for (int k = 0; k < fi.size(); ++k) {
            const float d = std::abs(fi[k] - fr[k]) / std::max({fi[k], fr[k], floor});
            pairWorst = std::max(pairWorst, d);
            if (d > e.worst) {
                std::ostringstream os;
                os << "wo=(" << wo.x << "," << wo.y << "," << wo.z << ") wi=(" << wi.x << "," << wi.y << "," << wi.z << ") lane " << k
                   << ": f*(wo,wi)=" << fi[k] << " f(wi,wo)=" << fr[k];
                e.worst = d;
                e.where = os.str();
            }
        }
        off += pairWorst > 1e-3f;
    }
    e.offShare = float(off) / float(pairs);
    return e;
}

/// The same identity for the delta lobes, whose values are coefficients of Dirac distributions:
/// a sample wo → wi of coefficient c = f |cos θi| (materials/bsdf.h) in importance mode must equal
/// the radiance coefficient of the reverse sample wi → wo over η², η the relative index crossed
/// (BSDFSample::eta; 1 for reflection and pass-through): the Dirac distribution of refraction is
/// δ(ω − T(ω')) with the Jacobian (η_o/η_i)² of the solid angles (Veach eq. 5.12). The reverse
/// sample is found by scanning the lobe choice uc for a delta sample with the same lobe back at wo.
AdjointError deltaAdjointError(const BSDF& bsdf, uint64_t seed, int directions = 40) {
    Sampler rng(seed);
    AdjointError e;
    for (int i = 0; i < directions; ++i) {
        const vec3 wo = randomDirection(rng);
        for (int k = 0; k < 16; ++k) {
            const auto s = bsdf.sample(wo, (k + 0.5f) / 16, rng.get2D(), TransportMode::Importance);
            if (!s || !s->isSpecular() || !(s->pdf > 0)) continue;
            std::optional<BSDFSample> back;
            for (int j = 0; j < 64 && !back; ++j) {
                const auto r = bsdf.sample(s->wi, (j + 0.5f) / 64, vec2(0.5f), TransportMode::Radiance);
                if (r && r->isSpecular() && r->flags == s->flags && glm::length(r->wi - wo) < 1e-3f) back = r;
            }
            if (!back) {
                e.worst = 1.0f;
                e.where = "no reverse delta sample";
                continue;
            }
            const SampledSpectrum ci = s->f * std::abs(s->wi.z), cr = back->f * (std::abs(wo.z) / sqr(s->eta));
            for (int c = 0; c < ci.size(); ++c) {
                const float d = std::abs(ci[c] - cr[c]) / std::max({ci[c], cr[c], 1e-5f});
                if (d > e.worst) {
                    std::ostringstream os;
                    os << "wo=(" << wo.x << "," << wo.y << "," << wo.z << ") lobe " << s->flags << " lane " << c << ": c*=" << ci[c]
                       << " reverse c/eta^2=" << cr[c];
                    e.worst = d;
                    e.where = os.str();
                }
            }
        }
    }
    return e;
}

std::vector<std::string> registeredMaterials() {
    std::vector<std::string> names;
    for (const std::string& n : MaterialRegistry::instance().names())
        if (n.find("test") == std::string::npos) names.push_back(n);
    return names;
}

class AdjointBSDF : public ::testing::TestWithParam<std::string> {};

TEST_P(AdjointBSDF, ImportanceModeIsTheAdjointOfRadianceMode) {
    const stress::MaterialStress cfg = stress::stressConfigsFor(GetParam());
    ASSERT_TRUE(cfg.known) << GetParam() << " has no stress configurations (tests/support/stress_configs.cpp)";
    const SampledWavelengths sets[] = {SampledWavelengths::rgb(defaultChannelWavelengths()), SampledWavelengths::sampleVisible(0.37f, 4)};
    AdjointError worst;
    float offShare = 0;
    for (size_t ci = 0; ci < cfg.cases.size(); ++ci) {
        const auto mat = MaterialRegistry::instance().create(*cfg.cases[ci].props);
        for (int si = 0; si < 2; ++si) {
            Arena arena;
            ShadingPoint sp;
            sp.tex.uv = vec2(0.3f, 0.6f);
            SampledWavelengths wl = sets[si];
            const BSDF* bsdf = mat->getBSDF(sp, wl, arena);
            if (!bsdf) continue;
            for (const AdjointError& e : {adjointError(*bsdf, 1000 * ci + si), deltaAdjointError(*bsdf, 1000 * ci + si + 7)}) {
                offShare = std::max(offShare, e.offShare);
                if (e.worst > worst.worst) worst = {e.worst, 0, "[" + cfg.cases[ci].label + (si ? " | N=4] " : " | RGB] ") + e.where};
            }
        }
    }
    std::cout << "ADJOINT | " << GetParam() << " | pairs > 1e-3 apart " << offShare << " | max relative difference " << worst.worst
              << (worst.where.empty() ? "" : " at " + worst.where) << "\n";
    EXPECT_LT(offShare, 0.03f) << GetParam();
    EXPECT_LT(worst.worst, 0.05f) << GetParam() << ": " << worst.where;
}

INSTANTIATE_TEST_SUITE_P(Registered, AdjointBSDF, ::testing::ValuesIn(registeredMaterials()),
                         [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

/// A BSDF that is not reciprocal and ignores the transport mode (what a forgotten adjoint looks like).
class IgnoresTheMode final : public BSDF {
public:
    SampledSpectrum eval(const vec3& wo, const vec3& wi, TransportMode) const override {
        return SampledSpectrum(3, wo.z > 0 && wi.z > 0 ? (0.2f + 0.6f * wo.z) / 3.14159f : 0.0f);
    }
    std::optional<BSDFSample> sample(const vec3&, float, const vec2&, TransportMode) const override { return std::nullopt; }
    float pdf(const vec3&, const vec3&, TransportMode) const override { return 0.0f; }
    uint32_t flags() const override { return kBSDFReflection | kBSDFDiffuse; }
};

TEST(AdjointBSDF, AProbeThatIgnoresTheModeIsCaught) {
    const IgnoresTheMode probe;
    const AdjointError e = adjointError(probe, 7);
    EXPECT_GT(e.worst, 0.1f);
    EXPECT_GT(e.offShare, 0.1f);  // it is nonzero on the quarter of the pairs above the surface
}

/// A smooth glass whose importance mode keeps the radiance BTDF's 1/η² (the classic mistake).
class GlassWithRadianceScalingInBothModes final : public BSDF {
public:
    SampledSpectrum eval(const vec3&, const vec3&, TransportMode) const override { return SampledSpectrum(3); }
    std::optional<BSDFSample> sample(const vec3& wo, float, const vec2&, TransportMode) const override {
        const float eta = wo.z > 0 ? 1.5f : 1.0f / 1.5f;  // η of wi's side relative to wo's
        const float sin2T = (1 - wo.z * wo.z) / (eta * eta);
        if (sin2T >= 1) return std::nullopt;
        BSDFSample s;
        s.wi = glm::normalize(vec3(-wo.x / eta, -wo.y / eta, -std::copysign(std::sqrt(1 - sin2T), wo.z)));
        s.pdf = 1;
        s.eta = eta;
        s.flags = kBSDFTransmission | kBSDFSpecular;
        s.f = SampledSpectrum(3, 0.9f / (eta * eta) / std::abs(s.wi.z));
        return s;
    }
    float pdf(const vec3&, const vec3&, TransportMode) const override { return 0.0f; }
    uint32_t flags() const override { return kBSDFTransmission | kBSDFSpecular; }
};

TEST(AdjointBSDF, ADeltaLobeWithTheWrongModeIsCaught) {
    const GlassWithRadianceScalingInBothModes probe;
    EXPECT_GT(deltaAdjointError(probe, 3).worst, 0.5f);
}

}  // namespace
