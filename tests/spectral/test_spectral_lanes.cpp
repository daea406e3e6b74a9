// The per-wavelength lane loops (docs/performance.md): every vectorised path is checked against the
// one-wavelength form it replaced, bit for bit where the operations are the same, and within a
// stated bound where the float logarithm replaced libm's double log.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <vector>

#include "core/rng.h"
#include "spectral/cie.h"
#include "spectral/d65_spectrum.h"
#include "spectral/lane_dispatch.h"
#include "spectral/piecewise_linear_spectrum.h"
#include "spectral/rgb_spectrum.h"
#include "spectral/rgb_upsampling.h"
#include "spectral/spectrum_factory.h"
#include "spectral/wavelengths.h"
#include "spectral/xyz.h"

using namespace iris;

namespace {

/// The three components equal as floats (== per component, as ASSERT_EQ on each).
::testing::AssertionResult sameVec3(const vec3& a, const vec3& b) {
    if (a.x == b.x && a.y == b.y && a.z == b.z) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "(" << a.x << ", " << a.y << ", " << a.z << ") vs (" << b.x << ", " << b.y
                                         << ", " << b.z << ")";
}

// The sampler as it was before the lane loop (spectral/wavelengths.cpp at commit 1ea2fde): t in
// float, then λ = c + ½ ln((1 + t)/(1 − t))/a with libm's double log, and p = (1 − t²)/norm.
constexpr float kA = 0.0072f, kC = 538.0f;
float cdfRaw(float l) { return std::tanh(kA * (l - kC)) / kA; }
struct OldSample {
    float lambda, pdf;
};
OldSample oldSampleVisible(float u) {
    static const float norm = cdfRaw(kLambdaMax) - cdfRaw(kLambdaMin);
    static const float tanhMin = std::tanh(kA * (kLambdaMin - kC));
    static const double invNorm = 1.0 / double(norm);
    const float t = std::clamp(tanhMin + u * kA * norm, -0.99999994f, 0.99999994f);
    const double td = t;
    const float lambda = float(double(kC) + (0.5 / double(kA)) * std::log((1.0 + td) / (1.0 - td)));
    return {std::clamp(lambda, kLambdaMin, kLambdaMax), float((1.0 - td * td) * invNorm)};
}

// The sigmoid before the clamp: an infinity test, then the formula.
float oldSigmoid(float x) {
    if (std::isinf(x)) return x > 0 ? 1.0f : 0.0f;
    return 0.5f + x / (2.0f * std::sqrt(1.0f + x * x));
}

// toXYZ as the plain loop it was (spectral/xyz.cpp at commit 1ea2fde).
vec3 oldToXYZ(const SampledSpectrum& L, const SampledWavelengths& wl) {
    vec3 sum(0.0f);
    for (int i = 0; i < wl.size(); ++i) {
        const float pdf = wl.pdf(i);
        if (pdf == 0.0f) continue;
        sum += (L[i] / pdf) * cie::xyzBar(wl.lambda(i));
    }
    return sum * (float(1.0 / cie::yIntegral()) / float(wl.size()));
}

// Random floats of every magnitude in [2^-20, 2^20] (log-uniform), both signs when asked.
float logUniform(Pcg32& rng, float lo, float hi, bool signed_) {
    const float v = std::exp(std::log(lo) + rng.uniform() * (std::log(hi) - std::log(lo)));
    return signed_ && rng.uniform() < 0.5f ? -v : v;
}

}  // namespace

TEST(SpectralLanes, LogPositiveMatchesLibm) {
    // The series is truncated below 2.3e-9 relative; what remains is float rounding in s, the
    // series and the sum, a few ulps of the result. Bound: 4 ulps of |ln x| (plus 2^-149 absolute
    // near x = 1, where ln x → 0 and the error is that of m − 1 = exact times a rounded s).
    Pcg32 rng(5, 9);
    double worstUlps = 0;
    for (int k = 0; k < 400000; ++k) {
        const float x = k < 6 ? std::array<float, 6>{1.0f, 0.5f, 2.0f, 0.70710677f, 1.4142135f, 1e-30f}[k]
                              : logUniform(rng, 1e-30f, 1e30f, false);
        const double ref = std::log(double(x));
        const double got = logPositive(x);
        const double ulp = std::max(double(std::nextafter(float(std::abs(ref)), INFINITY) - float(std::abs(ref))), 1e-45);
        worstUlps = std::max(worstUlps, std::abs(got - ref) / ulp);
        ASSERT_LE(std::abs(got - ref), 4.0 * ulp) << x;
    }
    // Near 1 (where the reduction keeps k = 0 and s is tiny).
    for (float x = 0.999f; x < 1.001f; x = std::nextafter(x, 2.0f)) {
        const double ref = std::log(double(x));
        const double ulp = std::max(double(std::nextafter(float(std::abs(ref)), INFINITY) - float(std::abs(ref))), 1e-45);
        ASSERT_LE(std::abs(double(logPositive(x)) - ref), 4.0 * ulp) << x;
    }
    EXPECT_EQ(logPositive(1.0f), 0.0f);
    std::printf("logPositive: worst error %.2f ulps of ln x\n", worstUlps);
}

TEST(SpectralLanes, VisibleSamplerMatchesTheDoubleLogForm) {
    // Same t as before (the same float operations), so the pdf is bit-identical; λ now comes from
    // the float logarithm: |Δλ| ≤ (1/2a)·|Δ ln q| + rounding of λ, with q = (1 + t)/(1 − t) rounded
    // in float (≤ 3 half-ulps, 1.8e-7 relative → 1.3e-5 nm), logPositive's few ulps of ln q
    // (|ln q| ≤ 4.2: ≤ 4·4.8e-7·69.4 nm ≈ 1.3e-4 nm at most, far less in practice) and the float
    // sum c + (1/2a) ln q (≤ 1 ulp of λ, 6.1e-5 nm). Bound: 1.2e-4 nm, two ulps of λ at 830 nm.
    Pcg32 rng(21, 4);
    double worst = 0;
    for (int k = 0; k < 500000; ++k) {
        const float u = k < 4 ? std::array<float, 4>{0.0f, 0.5f, 0.99999994f, 1e-7f}[k] : rng.uniform();
        const OldSample ref = oldSampleVisible(u);
        const SampledWavelengths wl = SampledWavelengths::sampleVisible(u, 1);
        ASSERT_EQ(wl.pdf(0), ref.pdf) << u;
        ASSERT_GE(wl.lambda(0), kLambdaMin);
        ASSERT_LE(wl.lambda(0), kLambdaMax);
        worst = std::max(worst, double(std::abs(wl.lambda(0) - ref.lambda)));
        ASSERT_LE(std::abs(wl.lambda(0) - ref.lambda), 1.2e-4f) << u;
        ASSERT_EQ(sampleVisibleWavelength(u), wl.lambda(0));
    }
    std::printf("sampleVisible: worst |Δλ| vs the double-log form %.3g nm\n", worst);
}

TEST(SpectralLanes, HeroLanesEqualOneAtATimeSampling) {
    // Lane i of sampleVisible(u, n) is the one-wavelength sample at (u + i/n) mod 1, bit for bit;
    // the padding lanes up to a multiple of 4 have pdf 0 and an in-range wavelength; the cached
    // D65 lanes equal cie::d65.
    Pcg32 rng(3, 8);
    for (int n = 1; n <= kMaxWavelengths; ++n) {
        for (int rep = 0; rep < 200; ++rep) {
            const float u = rep == 0 ? 0.0f : rep == 1 ? 0.99999994f : rng.uniform();
            const SampledWavelengths wl = SampledWavelengths::sampleVisible(u, n);
            const SampledWavelengths wu = SampledWavelengths::sampleUniform(u, n);
            for (int i = 0; i < n; ++i) {
                float up = u + float(i) / n;
                if (up >= 1.0f) up -= 1.0f;
                const OldSample ref = oldSampleVisible(up);
                ASSERT_EQ(wl.lambda(i), sampleVisibleWavelength(up)) << n << " " << i;
                ASSERT_EQ(wl.pdf(i), ref.pdf);
                ASSERT_EQ(wl.d65Lanes()[i], cie::d65(wl.lambda(i)));
                ASSERT_EQ(wu.lambda(i), kLambdaMin + up * (kLambdaMax - kLambdaMin));
                ASSERT_EQ(wu.pdf(i), 1.0f / (kLambdaMax - kLambdaMin));
                ASSERT_EQ(wu.d65Lanes()[i], cie::d65(wu.lambda(i)));
            }
            for (int i = n; i < SampledSpectrum::paddedSize(n); ++i) {
                ASSERT_EQ(wl.pdfs()[i], 0.0f);
                ASSERT_EQ(wu.pdfs()[i], 0.0f);
                ASSERT_GE(wl.lambdas()[i], kLambdaMin);
                ASSERT_LE(wl.lambdas()[i], kLambdaMax);
            }
        }
    }
    const SampledWavelengths rgb = SampledWavelengths::rgb(defaultChannelWavelengths());
    EXPECT_EQ(rgb.pdfs()[3], 0.0f);
}

TEST(SpectralLanes, HeroLanesMatchThePdfHistogram) {
    // Chi-square of every lane of sampleVisible(u, 8) (200k paths, 1.6M wavelengths, 47 bins of
    // 10 nm) against the integrated pdf; each lane is marginally distributed as the pdf.
    const int bins = 47, paths = 200000, n = 8;
    std::vector<double> counts(bins, 0.0);
    Pcg32 rng(12, 1);
    for (int k = 0; k < paths; ++k) {
        const SampledWavelengths wl = SampledWavelengths::sampleVisible(rng.uniform(), n);
        for (int i = 0; i < n; ++i) counts[std::min(bins - 1, int((wl.lambda(i) - kLambdaMin) / 10.0f))] += 1;
    }
    double chi2 = 0;
    for (int b = 0; b < bins; ++b) {
        double p = 0;
        for (int k = 0; k < 100; ++k) p += visibleWavelengthPdf(kLambdaMin + 10.0f * b + 0.1f * (k + 0.5f)) * 0.1;
        const double expected = p * paths * n;
        chi2 += sqr(counts[b] - expected) / expected;
    }
    // The lanes of one path are stratified (not independent), which only lowers the variance of
    // the counts; 46 degrees of freedom: the 1e-6 upper quantile is about 110.
    EXPECT_LT(chi2, 110.0);
}

TEST(SpectralLanes, D65LanesEqualTheScalarLookup) {
    Pcg32 rng(8, 2);
    std::vector<float> l;
    for (float x : {300.0f, 359.999f, 360.0f, 360.5f, 365.0f, 829.0f, 829.999f, 830.0f, 830.001f, 900.0f, -1.0f,
                    std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()})
        l.push_back(x);
    for (int k = 0; k < 4000; ++k) l.push_back(350.0f + 490.0f * rng.uniform());
    for (int k = 360; k <= 830; ++k) l.push_back(float(k));
    while (l.size() % 4) l.push_back(500.0f);
    std::vector<float> d(l.size());
    cie::d65Lanes(l.data(), int(l.size()), d.data());
    for (size_t j = 0; j < l.size(); ++j) ASSERT_EQ(d[j], cie::d65(l[j])) << l[j];
    // Four at a time (N ≤ 4 has its own constant-count path), edge values included; the comparison
    // can fail: the lookup one nanometre off differs.
    int offByOneDiffers = 0;
    for (size_t j0 = 0; j0 < l.size(); j0 += 4) {
        float four[4];
        cie::d65Lanes(l.data() + j0, 4, four);
        for (size_t j = 0; j < 4; ++j) {
            ASSERT_EQ(std::bit_cast<uint32_t>(four[j]), std::bit_cast<uint32_t>(cie::d65(l[j0 + j]))) << l[j0 + j];
            offByOneDiffers += four[j] != cie::d65(l[j0 + j] + 1.0f);
        }
    }
    EXPECT_GT(offByOneDiffers, 4000);
}

TEST(SpectralLanes, ToXYZEqualsThePlainLoop) {
    Pcg32 rng(4, 4);
    for (int n = 1; n <= kMaxWavelengths; ++n) {
        for (int rep = 0; rep < 300; ++rep) {
            SampledWavelengths wl = SampledWavelengths::sampleVisible(rng.uniform(), n);
            if (rep % 3 == 0) wl.terminateSecondary();
            SampledSpectrum L(n);
            for (int i = 0; i < n; ++i) L[i] = rng.uniform() < 0.1f ? 0.0f : logUniform(rng, 1e-4f, 1e3f, rep % 5 == 0);
            if (wl.secondaryTerminated())
                for (int i = 1; i < n; ++i) L[i] = std::numeric_limits<float>::quiet_NaN();  // never read
            ASSERT_TRUE(sameVec3(toXYZ(L, wl), oldToXYZ(L, wl))) << n;
        }
    }
}

TEST(SpectralLanes, SigmoidEqualsTheOldFormulaAndHasTheRightLimits) {
    Pcg32 rng(6, 6);
    for (int k = 0; k < 400000; ++k) {
        const float x = k == 0 ? 0.0f : logUniform(rng, 1e-20f, 9.2e18f, true);
        ASSERT_EQ(SigmoidPolynomial::sigmoid(x), oldSigmoid(x)) << x;
    }
    // Where the old formula overflowed (x² = inf for |x| ≥ 2^64) it returned ½.
    for (float x : {1.8446744e19f, 1e20f, 1e30f, std::numeric_limits<float>::max(), INFINITY}) {
        EXPECT_EQ(SigmoidPolynomial::sigmoid(x), 1.0f) << x;
        EXPECT_EQ(SigmoidPolynomial::sigmoid(-x), 0.0f) << x;
    }
    EXPECT_EQ(oldSigmoid(1e20f), 0.5f);  // the bug this fixes
    EXPECT_TRUE(std::isnan(SigmoidPolynomial::sigmoid(std::numeric_limits<float>::quiet_NaN())));
    // Monotone through the clamp threshold.
    EXPECT_LE(SigmoidPolynomial::sigmoid(9.2e18f), SigmoidPolynomial::sigmoid(9.3e18f));
    EXPECT_GE(SigmoidPolynomial::sigmoid(-9.2e18f), SigmoidPolynomial::sigmoid(-9.3e18f));
}

TEST(SpectralLanes, RgbSpectrumSampleEqualsEvalAtEveryLane) {
    // The lane loops of RGBSpectrum::sample against eval(λ) one wavelength at a time, bit for bit,
    // for every kind, greys and colours, bright and dark, every N.
    Pcg32 rng(9, 1);
    std::vector<SpectrumPtr> spectra;
    for (SpectrumKind kind : {SpectrumKind::Reflectance, SpectrumKind::Unbounded, SpectrumKind::Illuminant}) {
        spectra.push_back(makeRGBSpectrum(vec3(0.45f), kind));
        spectra.push_back(makeRGBSpectrum(vec3(0.6f, 0.08f, 0.05f), kind));
        spectra.push_back(makeRGBSpectrum(vec3(0.01f, 0.02f, 0.001f), kind));
        for (int k = 0; k < 6; ++k) {
            const float s = kind == SpectrumKind::Reflectance ? 1.0f : 5.0f;
            spectra.push_back(makeRGBSpectrum(s * vec3(rng.uniform(), rng.uniform(), rng.uniform()), kind));
        }
    }
    for (const SpectrumPtr& s : spectra) {
        for (int n = 1; n <= kMaxWavelengths; ++n) {
            for (int rep = 0; rep < 20; ++rep) {
                const SampledWavelengths wl = SampledWavelengths::sampleVisible(rng.uniform(), n);
                const SampledSpectrum v = s->sample(wl);
                ASSERT_EQ(v.size(), n);
                for (int i = 0; i < n; ++i) ASSERT_EQ(v[i], s->eval(wl.lambda(i))) << n << " " << i;
            }
        }
    }
}

TEST(SpectralLanes, WeightedCmfSumEqualsThePlainLoop) {
    Pcg32 rng(2, 7);
    for (int n = 1; n <= 70; ++n) {
        std::vector<float> l(size_t(n + 3) & ~size_t(3)), w(l.size());
        for (int rep = 0; rep < 50; ++rep) {
            for (size_t j = 0; j < l.size(); ++j) {
                l[j] = rep % 7 == 0 && j % 5 == 0 ? 340.0f + 510.0f * rng.uniform() : 360.0f + 470.0f * rng.uniform();
                w[j] = rng.uniform() < 0.1f ? 0.0f : logUniform(rng, 1e-3f, 1e3f, true);
            }
            vec3 ref(0.0f);
            for (int j = 0; j < n; ++j) ref += w[j] * cie::xyzBar(l[j]);
            ASSERT_TRUE(sameVec3(cie::weightedXyzBarSum(l.data(), w.data(), n), ref)) << n;
        }
    }
}

TEST(SpectralLanes, PiecewiseLinearBucketLookupEqualsBinarySearch) {
    // eval finds its interval from a bucket grid and a short walk; it must give exactly the value
    // of the binary-search form it replaced, for irregular tables (clustered and sparse samples),
    // at random wavelengths, at every sample and its float neighbours, and just inside the ends.
    Pcg32 rng(13, 3);
    for (int table = 0; table < 60; ++table) {
        const int count = 2 + int(rng.uniform() * 80);
        std::vector<float> l, v;
        float x = 200.0f + 300.0f * rng.uniform();
        for (int k = 0; k < count; ++k) {
            l.push_back(x);
            v.push_back(logUniform(rng, 1e-3f, 10.0f, true));
            x += table % 3 == 0 ? logUniform(rng, 1e-3f, 200.0f, false) : 0.5f + 20.0f * rng.uniform();
        }
        const PiecewiseLinearSpectrum s(l, v, SpectrumKind::Unbounded);
        auto reference = [&](float lambda) {
            if (lambda <= l.front()) return v.front();
            if (lambda >= l.back()) return v.back();
            const size_t i = size_t(std::upper_bound(l.begin(), l.end(), lambda) - l.begin());
            const float t = (lambda - l[i - 1]) / (l[i] - l[i - 1]);
            return (1.0f - t) * v[i - 1] + t * v[i];
        };
        std::vector<float> probes;
        for (int k = 0; k < 2000; ++k) probes.push_back(l.front() - 10.0f + (l.back() - l.front() + 20.0f) * rng.uniform());
        for (float li : l)
            for (float p : {std::nextafter(li, -INFINITY), li, std::nextafter(li, INFINITY)}) probes.push_back(p);
        for (float p : probes) ASSERT_EQ(s.eval(p), reference(p)) << table << " " << p;
    }
    const PiecewiseLinearSpectrum s({400, 500}, {1, 2}, SpectrumKind::Unbounded);
    EXPECT_TRUE(std::isnan(s.eval(std::numeric_limits<float>::quiet_NaN())));
    EXPECT_EQ(s.eval(INFINITY), 2.0f);
    EXPECT_EQ(s.eval(-INFINITY), 1.0f);
}

TEST(SpectralLanes, D65SpectrumSampleEqualsEval) {
    const D65Spectrum d(2.5f);
    Pcg32 rng(1, 1);
    for (int n = 1; n <= kMaxWavelengths; ++n) {
        const SampledWavelengths wl = SampledWavelengths::sampleVisible(rng.uniform(), n);
        const SampledSpectrum v = d.sample(wl);
        for (int i = 0; i < n; ++i) ASSERT_EQ(v[i], d.eval(wl.lambda(i)));
    }
    const SampledSpectrum rgb = d.sample(SampledWavelengths::rgb(defaultChannelWavelengths()));
    for (int c = 0; c < 3; ++c) EXPECT_EQ(rgb[c], d.rgbValue()[c]);
}

TEST(SpectralLanes, Avx2AndBaselineBuildsAreBitIdentical) {
    // Every dispatched kernel (spectral/lane_dispatch.h) run in both builds on the same inputs.
    // Where the CPU lacks AVX2 both runs take the baseline build and the test is vacuous.
    std::printf("AVX2 build %s on this CPU\n", lanes::useAvx2() ? "available" : "not available");
    struct Run {
        std::vector<float> values;
    };
    const SpectrumPtr spectra[] = {makeRGBSpectrum(vec3(0.6f, 0.08f, 0.05f), SpectrumKind::Reflectance),
                                   makeRGBSpectrum(vec3(0.35f, 0.38f, 0.45f), SpectrumKind::Illuminant),
                                   makeRGBSpectrum(vec3(6.0f), SpectrumKind::Illuminant),
                                   makeRGBSpectrum(vec3(3.0f, 0.2f, 1.0f), SpectrumKind::Unbounded)};
    auto run = [&](bool baseline) {
        lanes::forceBaseline = baseline;
        Run r;
        Pcg32 rng(77, 5);
        for (int n = 1; n <= kMaxWavelengths; ++n) {
            for (int rep = 0; rep < 100; ++rep) {
                SampledWavelengths wl = SampledWavelengths::sampleVisible(rng.uniform(), n);
                for (int i = 0; i < SampledSpectrum::paddedSize(n); ++i) {
                    r.values.push_back(wl.lambdas()[i]);
                    r.values.push_back(wl.pdfs()[i]);
                    r.values.push_back(wl.d65Lanes()[i]);
                }
                for (const SpectrumPtr& s : spectra) {
                    const SampledSpectrum v = s->sample(wl);
                    for (int i = 0; i < n; ++i) r.values.push_back(v[i]);
                }
                if (rep % 4 == 0) wl.terminateSecondary();
                SampledSpectrum L(n);
                for (int i = 0; i < n; ++i) L[i] = logUniform(rng, 1e-3f, 1e3f, false);
                const vec3 xyz = toXYZ(L, wl);
                r.values.insert(r.values.end(), {xyz.x, xyz.y, xyz.z});
            }
        }
        lanes::forceBaseline = false;
        return r;
    };
    const Run a = run(false), b = run(true);
    ASSERT_EQ(a.values.size(), b.values.size());
    for (size_t k = 0; k < a.values.size(); ++k)
        ASSERT_EQ(std::bit_cast<uint32_t>(a.values[k]), std::bit_cast<uint32_t>(b.values[k])) << k;
}
