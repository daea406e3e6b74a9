// Granier & Heidrich model (thesis 000 §2.4, §3.1): values against an independent double-precision
// re-evaluation of the thesis' equations, RGB/spectral exactness, sampling (χ²), diffuse albedo.
#include <gtest/gtest.h>

#include <cmath>

#include "tests/support/bsdf_test_util.h"
#include "tests/support/thesis_test_util.h"

using namespace iris;
using namespace iris::test;

namespace {

// ---- Independent reference (double precision, written from the equations) ----
using D3 = glm::dvec3;

struct RefParams {
    D3 n0{0.24192, 0, 0.97030}, n1{0, 0, 1};
    double etaI = 1.0;
    double etaT[3] = {1.5, 1.6, 1.8};
    double lambda[3] = {645, 525, 445};
    double d = 76, e0 = 130, e1 = 130, ws = 0.7, wd = 0.3;
};

// Snell refraction by components: tangential part scaled by η_i/η_t, normal part from |t| = 1.
bool refRefract(const D3& w, const D3& n, double eta, D3* t) {
    const D3 wt = w - glm::dot(w, n) * n;  // tangential component of w
    const D3 tt = -eta * wt;               // tangential component of the refracted ray
    const double s2 = glm::dot(tt, tt);
    if (s2 >= 1) return false;
    *t = tt - std::sqrt(1 - s2) * n;  // travels into the film (against n)
    return true;
}

double refGranier(const RefParams& p, const D3& wi, const D3& wo, int c) {
    const D3 n0 = glm::normalize(p.n0), n1 = glm::normalize(p.n1);
    const double et = p.etaT[c], ei = p.etaI;
    double fs = 0;
    if (glm::dot(wi, n0) > 0 && glm::dot(wo, n0) > 0) {
        const double f = std::pow((ei - et) / (ei + et), 2);                          // 2.25
        auto schlick = [&](double cosv) { return f + (1 - f) * std::pow(1 - cosv, 5); };  // 2.24
        const D3 wri = 2 * glm::dot(wi, n0) * n0 - wi;
        const double fr = schlick(glm::dot(wi, n0)) * std::pow(std::max(0.0, glm::dot(wri, wo)), p.e0);  // 2.23
        D3 wti, wto;
        double ft = 0, phi = 0;
        if (refRefract(wi, n0, ei / et, &wti) && refRefract(wo, n0, ei / et, &wto)) {
            const D3 wrti = wti - 2 * glm::dot(wti, n1) * n1;
            ft = (1 - schlick(glm::dot(wi, n0))) * std::pow(std::max(0.0, glm::dot(wrti, -wto)), p.e1) *
                 (1 - schlick(-glm::dot(wto, n0)));                                        // 2.27
            phi = M_PI * et * p.d / p.lambda[c] * glm::dot(wti + wto, -n0);               // 2.28
        }
        fs = fr + ft + 2 * std::cos(2 * phi) * std::sqrt(fr * ft);  // 2.29–2.30
    }
    const double Td = 80.0 / 21.0 * ei * et / std::pow(et + ei, 2);                                 // 2.32
    const double fd = 1 + 2 * std::cos(4 * M_PI * et * p.d / p.lambda[c]) * std::sqrt(Td * (1 - Td));  // 2.34
    return p.ws * fs + p.wd * fd / M_PI;                                                             // 2.35
}

std::shared_ptr<Properties> table31Props(const RefParams& r) {
    return makeProps("granier", {{"n0", VectorValue{vec3(r.n0)}},
                                 {"n1", VectorValue{vec3(r.n1)}},
                                 {"eta_i", float(r.etaI)},
                                 {"eta_t", RGBValue{vec3(r.etaT[0], r.etaT[1], r.etaT[2])}},
                                 {"thickness", float(r.d)},
                                 {"e0", float(r.e0)},
                                 {"e1", float(r.e1)},
                                 {"ws", float(r.ws)},
                                 {"wd", float(r.wd)}});
}

// The outgoing direction whose internal path is the perfect mirror path of wi (peak of ft).
D3 internalMirror(const RefParams& p, const D3& wi, int c) {
    const D3 n0 = glm::normalize(p.n0);
    D3 wti;
    EXPECT_TRUE(refRefract(wi, n0, p.etaI / p.etaT[c], &wti));
    const D3 up = wti - 2 * glm::dot(wti, p.n1) * p.n1;  // travelling up inside the film
    D3 out(0.0);  // refraction of `up` out of the film (zero under total internal reflection)
    if (!refRefract(-up, -n0, p.etaT[c] / p.etaI, &out)) return D3(0.0);
    return out;
}

}  // namespace

TEST(Granier, MatchesIndependentEvaluationTable31) {
    const RefParams r;
    auto inst = makeBSDF(*table31Props(r), SampledWavelengths::rgb(defaultChannelWavelengths()));
    std::vector<std::pair<D3, D3>> pairs;
    const D3 n0 = glm::normalize(r.n0);
    for (double ci : {0.95, 0.7, 0.4}) {
        const D3 wi(-std::sqrt(1 - ci * ci), 0, ci);
        pairs.push_back({wi, 2 * glm::dot(wi, n0) * n0 - wi});                       // Phong peak of fr
        pairs.push_back({wi, internalMirror(r, wi, 1)});                              // peak of ft (green)
        pairs.push_back({wi, glm::normalize(internalMirror(r, wi, 0) + D3(0, 0.02, 0))});  // near it
        pairs.push_back({wi, D3(-0.3, 0.4, std::sqrt(0.75))});                        // diffuse only
    }
    int checked = 0;
    double maxSpecular = 0;
    for (const auto& [wi, wo] : pairs) {
        if (wo.z <= 0 || glm::length(wo) < 0.5) continue;
        const SampledSpectrum f = inst.bsdf->eval(vec3(wo), vec3(wi), TransportMode::Radiance);
        for (int c = 0; c < 3; ++c) {
            const double ref = refGranier(r, wi, wo, c);
            maxSpecular = std::max(maxSpecular, ref - r.wd * 1.6 / M_PI);
            EXPECT_NEAR(f[c], ref, 3e-5 * std::max(1.0, ref)) << "c=" << c << " wi=" << wi.z << " wo=" << wo.x;
            ++checked;
        }
    }
    EXPECT_GE(checked, 30);
    EXPECT_GT(maxSpecular, 0.1);  // the chosen pairs really exercise the Phong lobes
}

TEST(Granier, RGBModeIsDeterministicAndSpectralN1MatchesChannels) {
    const RefParams r;
    auto a = makeBSDF(*table31Props(r), SampledWavelengths::rgb(defaultChannelWavelengths()));
    auto b = makeBSDF(*table31Props(r), SampledWavelengths::rgb(defaultChannelWavelengths()));
    const vec3 lambdas = defaultChannelWavelengths();
    Pcg32 rng(11, 5);
    for (int k = 0; k < 200; ++k) {
        const vec3 wo = sampleCosineHemisphere(vec2(rng.uniform(), rng.uniform()));
        const vec3 wi = sampleCosineHemisphere(vec2(rng.uniform(), rng.uniform()));
        const SampledSpectrum fa = a.bsdf->eval(wo, wi, TransportMode::Radiance);
        const SampledSpectrum fb = b.bsdf->eval(wo, wi, TransportMode::Radiance);
        for (int c = 0; c < 3; ++c) {
            ASSERT_EQ(fa[c], fb[c]);
            // Spectral mode at exactly λ_c: η_t interpolated across the channels is η_t[c].
            auto s = makeBSDF(*table31Props(r), exactWavelength(lambdas[c]));
            ASSERT_EQ(s.bsdf->eval(wo, wi, TransportMode::Radiance)[0], fa[c]) << "channel " << c;
        }
    }
}

TEST(Granier, SpectralModeInterpolatesEtaBetweenChannels) {
    // Between the channel wavelengths η_t is piecewise linear: at 585 nm (midway between 525 and
    // 645) with a diffuse-only material, fd uses η = 1.55 (thickness chosen so fd ≠ 1).
    RefParams r;
    r.ws = 0;
    r.n0 = D3(0, 0, 1);
    auto s = makeBSDF(*table31Props(r), exactWavelength(585.0f));
    const vec3 w(0, 0, 1);
    const double Td = 80.0 / 21.0 * 1.55 / std::pow(2.55, 2);
    const double fd = 1 + 2 * std::cos(4 * M_PI * 1.55 * 76 / 585.0) * std::sqrt(Td * (1 - Td));
    EXPECT_NEAR(s.bsdf->eval(w, w, TransportMode::Radiance)[0], r.wd * fd / M_PI, 2e-6);
}

TEST(Granier, DiffuseOnlyAlbedoIsWeightTimesFd) {
    // ws = 0: the BSDF is the constant wd·fd/π, so the albedo is wd·fd (reading of eq. 2.34).
    RefParams r;
    r.ws = 0;
    auto inst = makeBSDF(*table31Props(r), SampledWavelengths::rgb(defaultChannelWavelengths()));
    const auto alb = albedo(*inst.bsdf, dirFromCos(0.6f), 200000);
    for (int c = 0; c < 3; ++c) {
        const double expected = refGranier(r, D3(0, 0, 1), D3(0, 0, 1), c) * M_PI;
        EXPECT_NEAR(alb[c].mean, expected, 5 * alb[c].stderr_ + 1e-4) << "channel " << c;
    }
}

TEST(Granier, SamplingMatchesPdfChi2) {
    struct Case {
        vec3 n0, n1;
        float cosO, phi;
    };
    const vec3 z(0, 0, 1), tilt14(0.24192f, 0, 0.97030f);
    const Case cases[] = {{tilt14, z, 0.9f, 0.7f},
                          {tilt14, z, 0.3f, 0.7f},
                          {tilt14, z, 0.1f, 3.1f},
                          {z, z, 0.6f, 1.0f},
                          {z, z, 0.05f, 0.7f},  // Phong lobe cut by the horizon
                          {vec3(0.1736f, 0, 0.9848f), vec3(-0.2f, 0.1f, 0.97f), 0.6f, 0.7f}};  // tilted base
    Chi2Options opt;
    opt.numTests = 6;
    for (const Case& k : cases) {
        auto props = makeProps("granier", {{"n0", VectorValue{k.n0}},
                                           {"n1", VectorValue{k.n1}},
                                           {"eta_t", RGBValue{vec3(1.5f, 1.6f, 1.8f)}},
                                           {"e0", 40.0f},  // wider lobe: the χ² grid resolves it
                                           {"e1", 130.0f}});
        auto inst = makeBSDF(*props, SampledWavelengths::rgb(defaultChannelWavelengths()));
        const vec3 wo = dirFromCos(k.cosO, k.phi);
        const Chi2Result res = chi2Test(*inst.bsdf, wo, opt);
        EXPECT_TRUE(res.passed) << res.message;
        const ConsistencyResult cr = checkConsistency(*inst.bsdf, wo);
        EXPECT_EQ(cr.invalid, 0) << cr.message;
        EXPECT_LT(cr.maxRelErrF, 1e-5f);
        EXPECT_LT(cr.maxRelErrPdf, 1e-5f);
        const Estimate pi = pdfIntegral(*inst.bsdf, wo);
        EXPECT_LE(pi.mean, 1.0 + 5 * pi.stderr_);
    }
}

TEST(Granier, SampledMassMatchesPdfMass) {
    // Tilted base normal and grazing views: the pdf is non-zero at the horizon, where samples are
    // rejected. The fraction of accepted samples must equal ∫ pdf over the upper hemisphere
    // (fine midpoint quadrature), i.e. sample() draws exactly from pdf() restricted to z > 0.
    struct Case {
        vec3 n0, n1;
        float cosO;
    };
    const Case cases[] = {{vec3(0, 0, 1), vec3(0, 0, 1), 0.05f},
                          {vec3(0.1736f, 0, 0.9848f), vec3(-0.2f, 0.1f, 0.97f), 0.6f}};
    for (const Case& k : cases) {
        auto inst = makeBSDF("granier", {{"n0", VectorValue{k.n0}}, {"n1", VectorValue{k.n1}}, {"e0", 40.0f}});
        const vec3 wo = dirFromCos(k.cosO, 0.7f);
        const double mass = upperPdfMass(*inst.bsdf, wo);
        const auto [frac, sigma] = acceptedFraction(*inst.bsdf, wo);
        EXPECT_LT(mass, 0.999);  // the case really loses mass below the horizon
        EXPECT_NEAR(frac, mass, 4 * sigma + 1e-4);
        const ConsistencyResult cr = checkConsistency(*inst.bsdf, wo);
        EXPECT_EQ(cr.invalid, 0) << cr.message;
        EXPECT_LT(cr.maxRelErrPdf, 1e-5f);
    }
}

TEST(Granier, RejectsBadParameters) {
    EXPECT_THROW(makeBSDF("granier", {{"n0", VectorValue{vec3(0, 0, -1)}}}), Error);
    EXPECT_THROW(makeBSDF("granier", {{"e0", -1.0f}}), Error);
    EXPECT_THROW(makeBSDF("granier", {{"wavelengths", RGBValue{vec3(645, 0, 445)}}}), Error);
    EXPECT_THROW(makeBSDF("granier", {{"no_such", 1.0f}}), Error);
}

TEST(Granier, ImportanceModeIsTheAdjoint) {
    // Not reciprocal (Fresnel of the light side in eqs. 2.23, 2.27): importance transport must use
    // f*(wo, wi) = f(wi, wo).
    const RefParams r;
    auto inst = makeBSDF(*table31Props(r), SampledWavelengths::rgb(defaultChannelWavelengths()));
    const D3 wi(-0.6, 0, 0.8);
    const D3 wo = glm::normalize(internalMirror(r, wi, 1) + D3(0.01, 0.01, 0));
    const SampledSpectrum fr = inst.bsdf->eval(vec3(wo), vec3(wi), TransportMode::Radiance);
    const SampledSpectrum fi = inst.bsdf->eval(vec3(wi), vec3(wo), TransportMode::Importance);
    for (int c = 0; c < 3; ++c) EXPECT_EQ(fr[c], fi[c]);
    EXPECT_GT(reciprocityError(*inst.bsdf, 2000, 6, 1e-3f), 1e-3f);  // really not reciprocal
}

TEST(Granier, ZeroExponentLobesAreHemispheres) {
    // e = 0: the Phong lobes are 1 on the hemisphere around their axis and 0 behind it (not
    // pow(0, 0) = 1 everywhere), so the lobe pdf (e0+1)/(2π) integrates to 1.
    auto inst = makeBSDF("granier", {{"e0", 0.0f}, {"e1", 0.0f}, {"n0", VectorValue{vec3(0.24192f, 0, 0.97030f)}}});
    const vec3 wo = dirFromCos(0.5f, 0.3f);
    const Estimate p = pdfIntegral(*inst.bsdf, wo);
    EXPECT_LE(p.mean, 1.0 + 5 * p.stderr_);
    Chi2Options opt;
    const Chi2Result r = chi2Test(*inst.bsdf, wo, opt);
    EXPECT_TRUE(r.passed) << r.message;
}
