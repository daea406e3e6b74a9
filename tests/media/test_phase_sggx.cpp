// The sggx phase function (media/phase/sggx.cpp, sggx_math.h) against closed forms: S = I is
// isotropic scattering, ∫p = 1, the projected area σ(ω) = sqrt(ωᵀSω) equals ∫⟨ω,m⟩D(m)dm,
// reciprocity σ(wo)p(wo, wi) = σ(wi)p(wi, wo), χ² of the visible-normal sampling against the pdf
// (and a mismatched pdf rejected), a 6-channel grid S looked up at the scattering point, and bad
// matrices refused with their lines.
#include <gtest/gtest.h>

#include <cmath>

#include "core/rng.h"
#include "core/sampling.h"
#include "media/phase/sggx_math.h"
#include "tests/support/error_of.h"
#include "tests/support/phase_test_util.h"
#include "tests/support/vol_file.h"

using namespace iris;
using namespace iris::test;

namespace {

const vec3 kX(0.0f);  // where constant phase functions are evaluated (they ignore it)

std::shared_ptr<PhaseFunction> sggx(const SggxMatrix& S) {
    return makePhase("sggx", {{"S_xx", float(S.xx)}, {"S_yy", float(S.yy)}, {"S_zz", float(S.zz)},
                              {"S_xy", float(S.xy)}, {"S_xz", float(S.xz)}, {"S_yz", float(S.yz)}});
}

// Positive definite matrices: flakes like a fibre along z, like a surface facing z, and a general one.
const SggxMatrix kFibre{1.0, 1.0, 0.1, 0, 0, 0};
const SggxMatrix kSurface{0.1, 0.1, 1.0, 0, 0, 0};
const SggxMatrix kGeneral{1.0, 0.5, 0.3, 0.2, -0.1, 0.05};
const SggxMatrix kCases[] = {kFibre, kSurface, kGeneral};

const vec3 kDirections[] = {vec3(0, 0, 1), glm::normalize(vec3(0.3f, -0.5f, 0.8f)), glm::normalize(vec3(1, 0.2f, -0.1f))};

}  // namespace

TEST(PhaseSggx, IdentityIsIsotropicScattering) {
    // A sphere of flakes: D = 1/π, σ = 1, p = D / 4σ = 1/(4π) for every pair, also for S = 3I.
    for (const auto& p : {makePhase("sggx"), sggx(SggxMatrix{3, 3, 3, 0, 0, 0})}) {
        Pcg32 rng(3, 4);
        for (int i = 0; i < 1000; ++i) {
            const vec3 wo = sampleUniformSphere(vec2(rng.uniform(), rng.uniform()));
            const vec3 wi = sampleUniformSphere(vec2(rng.uniform(), rng.uniform()));
            if (glm::length(wo + wi) < 1e-3f) continue;
            EXPECT_NEAR(p->eval(kX, wo, wi), kInv4Pi, 1e-5f * kInv4Pi);
            const auto s = p->sample(kX, wo, vec2(rng.uniform(), rng.uniform()));
            ASSERT_TRUE(s);
            EXPECT_NEAR(s->pdf, kInv4Pi, 1e-5f * kInv4Pi);
        }
        // Its samples are uniform on the sphere: χ² against the isotropic pdf.
        const auto iso = makePhase("isotropic");
        EXPECT_TRUE(chi2Test(PhaseAsBSDF(*iso, kX, p.get()), glm::normalize(vec3(0.2f, 0.1f, 0.9f))).passed);
        // ... and a fibre's samples are not.
        const auto fibre = sggx(kFibre);
        EXPECT_FALSE(chi2Test(PhaseAsBSDF(*iso, kX, fibre.get()), glm::normalize(vec3(0.2f, 0.1f, 0.9f))).passed);
    }
}

TEST(PhaseSggx, ReciprocalWithItsProjectedArea) {
    for (const SggxMatrix& S : kCases) {
        const auto p = sggx(S);
        Pcg32 rng(8, 9);
        for (int i = 0; i < 2000; ++i) {
            const vec3 a = sampleUniformSphere(vec2(rng.uniform(), rng.uniform()));
            const vec3 b = sampleUniformSphere(vec2(rng.uniform(), rng.uniform()));
            const double lhs = sggxProjectedArea(S, dvec3(a)) * p->eval(kX, a, b);
            const double rhs = sggxProjectedArea(S, dvec3(b)) * p->eval(kX, b, a);
            EXPECT_NEAR(lhs, rhs, 1e-4 * std::max(lhs, 1e-3));
        }
    }
}

TEST(PhaseSggx, ProjectedAreaIsTheIntegralOfItsVisibleNormals) {
    // σ(ω) = ∫ ⟨ω, m⟩ D(m) dm (Heitz et al. 2015, supp. §1.3–1.4), by uniform sampling of m.
    for (const SggxMatrix& S : kCases) {
        for (const vec3& w : kDirections) {
            Pcg32 rng(21, 2);
            const int n = 400000;
            double sum = 0, sum2 = 0;
            for (int i = 0; i < n; ++i) {
                const dvec3 m(sampleUniformSphere(vec2(rng.uniform(), rng.uniform())));
                const double v = std::max(0.0, glm::dot(dvec3(w), m)) * sggxD(S, m) / kInv4Pi;
                sum += v;
                sum2 += v * v;
            }
            const double mean = sum / n, se = std::sqrt((sum2 / n - mean * mean) / n);
            EXPECT_NEAR(mean, sggxProjectedArea(S, dvec3(w)), 5 * se) << "S_zz=" << S.zz;
        }
    }
}

TEST(PhaseSggx, NormalisedAndSampledByItsPdf) {
    // The sample's value is D(m)/4σ at the sampled normal, eval's at the half vector recomputed
    // from the direction: they agree to float rounding of m (1e-3 relative where D is steep).
    for (const SggxMatrix& S : kCases)
        for (const vec3& wo : kDirections)
            expectNormalisedAndSampledByItsPdf(*sggx(S), kX, wo, int(std::size(kCases) * std::size(kDirections)), 1e-3f);
    // The harness sees a sampler of one matrix tested against the pdf of another.
    const auto a = sggx(kGeneral), b = sggx(SggxMatrix{1.0, 0.5, 0.36, 0.2, -0.1, 0.05});
    EXPECT_FALSE(chi2Test(PhaseAsBSDF(*b, kX, a.get()), kDirections[1]).passed);
}

TEST(PhaseSggx, GridParametersAreLookedUpAtTheScatteringPoint) {
    // A 2×1×1 grid: voxel 0 holds I, voxel 1 the general matrix; voxel centres at x = 1/4, 3/4.
    std::vector<float> v = {1, 1, 1, 0, 0, 0};
    for (double e : {kGeneral.xx, kGeneral.yy, kGeneral.zz, kGeneral.xy, kGeneral.xz, kGeneral.yz}) v.push_back(float(e));
    const std::string file = writeVolFile("iris_phase_sggx", "s.vol", ivec3(2, 1, 1), 6, v);
    const auto grid = phaseFromXml("<phase type=\"sggx\"><volume type=\"gridvolume\" name=\"S\"><string name=\"filename\" value=\"" +
                                   file + "\"/></volume></phase>");
    const auto iso = makePhase("sggx"), general = sggx(kGeneral);
    const auto mid = sggx(SggxMatrix{1.0, 0.75, 0.65, 0.1, -0.05, 0.025});  // the voxels' mean
    Pcg32 rng(4, 4);
    for (int i = 0; i < 200; ++i) {
        const vec3 wo = sampleUniformSphere(vec2(rng.uniform(), rng.uniform()));
        const vec3 wi = sampleUniformSphere(vec2(rng.uniform(), rng.uniform()));
        const float at0 = grid->eval(vec3(0.25f, 0.5f, 0.5f), wo, wi), at1 = grid->eval(vec3(0.75f, 0.5f, 0.5f), wo, wi);
        const float half = grid->eval(vec3(0.5f, 0.5f, 0.5f), wo, wi);
        EXPECT_NEAR(at0, iso->eval(kX, wo, wi), 1e-4f * at0);
        EXPECT_NEAR(at1, general->eval(kX, wo, wi), 1e-4f * at1);
        EXPECT_NEAR(half, mid->eval(kX, wo, wi), 1e-4f * half);
    }
}

TEST(PhaseSggx, BadMatricesAreRefusedWithTheirLine) {
    // Not positive definite: a negative diagonal entry, and |S_xy| > sqrt(S_xx S_yy).
    EXPECT_TRUE(contains(errorOf([] { phaseFromXml("<phase type=\"sggx\">\n<float name=\"S_zz\" value=\"-1\"/></phase>"); }),
                         "<string>:2: sggx: the matrix S_xx..S_yz = (1, 1, -1, 0, 0, 0) is not positive definite"));
    EXPECT_TRUE(contains(errorOf([] { phaseFromXml("<phase type=\"sggx\"><float name=\"S_xy\" value=\"1.5\"/></phase>"); }),
                         "is not positive definite"));
    // A grid with one indefinite voxel; a grid of 1 channel; S and the floats together.
    const std::string bad = writeVolFile("iris_phase_sggx", "bad.vol", ivec3(2, 1, 1), 6, {1, 1, 1, 0, 0, 0, 1, 1, 1, 2, 0, 0});
    const std::string one = writeVolFile("iris_phase_sggx", "one.vol", ivec3(1), 1, {1});
    auto withGrid = [](const std::string& f, const std::string& extra = "") {
        return "<phase type=\"sggx\">" + extra + "\n<volume type=\"gridvolume\" name=\"S\"><string name=\"filename\" value=\"" + f +
               "\"/></volume></phase>";
    };
    EXPECT_TRUE(contains(errorOf([&] { phaseFromXml(withGrid(bad)); }),
                         "<string>:3: sggx: S is not positive definite at voxel (1, 0, 0) of the grid"));
    EXPECT_TRUE(contains(errorOf([&] { phaseFromXml(withGrid(one)); }),
                         "<string>:3: parameter 'S' must be a volume of 6 channels, this gridvolume has 1"));
    EXPECT_TRUE(contains(errorOf([&] { phaseFromXml(withGrid(bad, "<float name=\"S_xx\" value=\"2\"/>")); }),
                         "<string>:2: sggx: give either the volume S or the six floats"));
}

TEST(PhaseSggx, SixChannelGridsAreNotSpectra) {
    // A 6-channel grid read where a medium needs a spectrum (sigma_t) is refused with its line.
    const std::string six = writeVolFile("iris_phase_sggx", "six.vol", ivec3(1), 6, {1, 1, 1, 0, 0, 0});
    const std::string err = sceneError("<medium type=\"heterogeneous\" id=\"m\">\n<volume type=\"gridvolume\" name=\"sigma_t\">"
                                       "<string name=\"filename\" value=\"" + six + "\"/></volume></medium>\n"
                                       "<shape type=\"sphere\"><ref name=\"interior\" id=\"m\"/></shape>\n");
    EXPECT_TRUE(contains(err, "<string>:3: parameter 'sigma_t': a gridvolume of 6 channels cannot give a spectrum")) << err;
}
