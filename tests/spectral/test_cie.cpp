// CIE tables and XYZ: published table values, the ∫ȳ normalisation (constant spectrum → illuminant
// E white), D65's chromaticity, and the film's Monte Carlo XYZ estimator against 1 nm quadrature.
#include <gtest/gtest.h>

#include "core/rng.h"
#include "spectral/blackbody_spectrum.h"
#include "spectral/cie.h"
#include "spectral/piecewise_linear_spectrum.h"
#include "spectral/spectrum_factory.h"
#include "spectral/xyz.h"

using namespace iris;

TEST(Cie, TableValuesAndInterpolation) {
    // CIE 015:2018 Table 1 entries at 555 nm and 600 nm.
    const vec3 a = cie::xyzBar(555.0f);
    EXPECT_FLOAT_EQ(a.x, 0.5120501f);
    EXPECT_FLOAT_EQ(a.y, 1.0f);
    EXPECT_FLOAT_EQ(a.z, 0.005749999f);
    EXPECT_FLOAT_EQ(cie::xBar(600.0f), 1.0622f);
    // Linear interpolation between 1 nm samples.
    EXPECT_NEAR(cie::yBar(555.5f), 0.5f * (1.0f + 0.9998567f), 1e-7);
    EXPECT_FLOAT_EQ(cie::xyzBar(360.0f).x, 0.0001299f);
    EXPECT_FLOAT_EQ(cie::xyzBar(830.0f).y, 4.5181e-07f);
    EXPECT_EQ(cie::xyzBar(359.9f), vec3(0.0f));
    EXPECT_EQ(cie::xyzBar(830.1f), vec3(0.0f));
    // D65: 100 at 560 nm; the CIE 1 nm table entry at 561 nm (99.6334) is the 5 nm interpolation.
    EXPECT_FLOAT_EQ(cie::d65(560.0f), 100.0f);
    EXPECT_NEAR(cie::d65(561.0f), 99.6334f, 1e-4);
    EXPECT_NEAR(cie::d65(452.0f), 117.169f, 1e-3);
    EXPECT_EQ(cie::d65(300.0f), 0.0f);
}

TEST(Cie, YIntegralAndEqualEnergyWhite) {
    // Σ ȳ over the 1 nm table (the value pbrt-v4 quotes as CIE_Y_integral is 106.856895).
    EXPECT_NEAR(cie::yIntegral(), 106.8569, 1e-3);
    // Normalisation: a constant spectrum 1 has Y = 1 exactly and X ≈ Z ≈ 1 (illuminant E).
    const dvec3 e = integrateXYZ([](float) { return 1.0f; });
    EXPECT_NEAR(e.y, 1.0, 1e-12);
    EXPECT_NEAR(e.x, 1.0, 1e-3);
    EXPECT_NEAR(e.z, 1.0, 1e-3);
    const dvec3 xy = chromaticity(e);
    EXPECT_NEAR(xy.x, 1.0 / 3.0, 2e-4);
    EXPECT_NEAR(xy.y, 1.0 / 3.0, 2e-4);
}

TEST(Cie, D65WhitePoint) {
    const SpectrumPtr d65 = makeD65Spectrum();
    const dvec3 xyz = integrateXYZ([&](float l) { return d65->eval(l); });
    EXPECT_NEAR(xyz.y, 1.0, 1e-6);
    const dvec3 xy = chromaticity(xyz);
    EXPECT_NEAR(xy.x, 0.3127, 1e-3);
    EXPECT_NEAR(xy.y, 0.3290, 1e-3);
    // The XYZ the IEC 61966-2-1 matrix maps to RGB (1, 1, 1).
    EXPECT_NEAR(xyz.x, 0.9505, 1e-3);
    EXPECT_NEAR(xyz.z, 1.089, 1e-3);
    // A scale multiplies Y.
    const SpectrumPtr d65x3 = makeD65Spectrum(3.0f);
    EXPECT_NEAR(integrateXYZ([&](float l) { return d65x3->eval(l); }).y, 3.0, 1e-5);
}

namespace {
// Mean and standard error of the per-sample XYZ estimates of spectrum `s` with n hero wavelengths.
struct McResult {
    dvec3 mean, stderr_;
};
template <typename Sampler>
McResult monteCarloXYZ(const Spectrum& s, int n, int samples, uint64_t seed, Sampler&& sampleWl, bool terminate) {
    Pcg32 rng(seed, 11);
    dvec3 sum(0.0), sum2(0.0);
    for (int k = 0; k < samples; ++k) {
        SampledWavelengths wl = sampleWl(rng.uniform(), n);
        if (terminate) wl.terminateSecondary();
        const dvec3 e(toXYZ(s.sample(wl), wl));
        sum += e;
        sum2 += e * e;
    }
    McResult r;
    r.mean = sum / double(samples);
    const dvec3 var = sum2 / double(samples) - r.mean * r.mean;
    r.stderr_ = glm::sqrt(glm::max(var, dvec3(0.0)) / double(samples));
    return r;
}
}  // namespace

TEST(Cie, MonteCarloXYZConvergesToQuadrature) {
    // A smooth but strongly coloured spectrum (4000 K blackbody) and a spiky measured-like one.
    const BlackbodySpectrum bb(4000.0f, 2.0f);
    const PiecewiseLinearSpectrum spiky({400, 450, 455, 460, 600, 610, 700}, {0.1f, 0.2f, 3.0f, 0.2f, 0.5f, 1.5f, 0.3f},
                                        SpectrumKind::Illuminant);
    const Spectrum* spectra[] = {&bb, &spiky};
    for (const Spectrum* s : spectra) {
        const dvec3 ref = integrateXYZ([&](float l) { return s->eval(l); });
        for (int n : {1, 4, 8}) {
            for (bool terminate : {false, true}) {
                const McResult r = monteCarloXYZ(*s, n, 100000, 1234 + n, SampledWavelengths::sampleVisible, terminate);
                for (int c = 0; c < 3; ++c) {
                    // 5 standard errors (+ the 1 nm quadrature's own error, far below 1e-4 relative).
                    EXPECT_NEAR(r.mean[c], ref[c], 5.0 * r.stderr_[c] + 1e-4 * std::abs(ref[c]))
                        << "n=" << n << " terminate=" << terminate << " component " << c;
                    EXPECT_GT(r.stderr_[c], 0.0);
                }
            }
        }
        const McResult u = monteCarloXYZ(*s, 4, 100000, 99, SampledWavelengths::sampleUniform, false);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(u.mean[c], ref[c], 5.0 * u.stderr_[c] + 1e-4 * std::abs(ref[c]));
    }
}

TEST(Cie, ToXYZSkipsZeroPdfEntries) {
    SampledWavelengths wl = SampledWavelengths::sampleVisible(0.25f, 4);
    wl.terminateSecondary();
    SampledSpectrum L(4, 1.0f);
    L[1] = L[2] = L[3] = std::numeric_limits<float>::quiet_NaN();  // must not be touched
    const vec3 xyz = toXYZ(L, wl);
    // Only the hero contributes: (1/N) · L0 · cmf(λ0) / pdf0', pdf0' = (hero pdf)/N, then / ∫ȳ.
    const vec3 expect = 0.25f * cie::xyzBar(wl.lambda(0)) / wl.pdf(0) / float(cie::yIntegral());
    EXPECT_TRUE(isFinite(xyz));
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(xyz[c], expect[c], 1e-5f * std::abs(expect[c]) + 1e-9f);
}
