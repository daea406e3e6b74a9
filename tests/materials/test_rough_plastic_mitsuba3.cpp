// roughplastic in Mitsuba 3 scenes (version 2.x/3.x; docs/scene_format.md): the coat's internal
// reflectance R_int = 2 · mean over 64 nodes of R(1/η, α, μ) μ (Mitsuba 3's estimate) instead of
// Mitsuba 0.6's Fdr = 1 − Td. Checked against an independent integration of the microfacet BRDF
// over outgoing directions (double precision, its own D, G1 and Fresnel), through the directional
// albedo of the material, and the choice by the version attribute of a scene file.
#include <gtest/gtest.h>

#include <cmath>

#include "core/quadrature.h"
#include "core/xml/xml_parser.h"
#include "materials/rough_plastic_tables.h"
#include "render/loader/scene_upgrade.h"
#include "tests/support/bsdf_test_util.h"

using namespace iris;
using namespace iris::test;

namespace {

constexpr double kBk7 = 1.5046;  // Mitsuba's "bk7" (the conformance scenes' int_ior)

/// Unpolarised dielectric Fresnel reflectance for cosθi > 0 and relative index eta = η_t/η_i
/// (Fresnel equations, Born & Wolf §1.5.2; 1 beyond the critical angle).
double fresnel(double ci, double eta) {
    const double s2t = (1.0 - ci * ci) / (eta * eta);
    if (s2t >= 1.0) return 1.0;
    const double ct = std::sqrt(1.0 - s2t);
    const double rs = (ci - eta * ct) / (ci + eta * ct), rp = (eta * ci - ct) / (eta * ci + ct);
    return 0.5 * (rs * rs + rp * rp);
}

/// Isotropic D(h) and Smith G1(v, h) (Walter et al. 2007 eqs. 25, 27 (exact), 33, 34).
struct Distribution {
    bool ggx;
    double alpha;
    double D(double cosH) const {
        if (cosH <= 0) return 0.0;
        const double c2 = cosH * cosH, t2 = (1.0 - c2) / c2, a2 = alpha * alpha;
        if (ggx) return a2 / (M_PI * c2 * c2 * (a2 + t2) * (a2 + t2));
        return std::exp(-t2 / a2) / (M_PI * a2 * c2 * c2);
    }
    double G1(double cosV, double vDotH) const {
        if (cosV <= 0 || vDotH <= 0) return 0.0;
        const double t = std::sqrt(std::max(0.0, 1.0 - cosV * cosV)) / cosV;
        if (t == 0) return 1.0;
        if (ggx) return 2.0 / (1.0 + std::sqrt(1.0 + alpha * alpha * t * t));
        const double a = 1.0 / (alpha * t);
        return 1.0 / (1.0 + 0.5 * (std::erf(a) - 1.0) + std::exp(-a * a) / (2.0 * a * std::sqrt(M_PI)));
    }
};

/// R(η, α, μ) = ∫_{H+} F(ωi·h) D(h) G1(ωi) G1(ωo) / (4 μ) dωo (the BRDF of Walter et al. 2007 eq. 20
/// times cosθo), by composite Gauss-Legendre over θo ∈ [0, π/2] and φo ∈ [0, π] (mirror symmetry).
double reflectanceOverOutgoing(const Distribution& d, double eta, double mu, int panels = 48) {
    const GaussLegendre& gl = gaussLegendre(8);
    const double si = std::sqrt(1.0 - mu * mu);
    const double wi[3] = {si, 0.0, mu};
    double sum = 0;
    for (int pt = 0; pt < panels; ++pt)
        for (int a = 0; a < 8; ++a) {
            const double th = (pt + gl.x[a]) * (M_PI / 2) / panels, wth = gl.w[a] * (M_PI / 2) / panels;
            const double so = std::sin(th), co = std::cos(th);
            for (int pp = 0; pp < panels; ++pp)
                for (int b = 0; b < 8; ++b) {
                    const double ph = (pp + gl.x[b]) * M_PI / panels, wph = gl.w[b] * M_PI / panels;
                    const double wo[3] = {so * std::cos(ph), so * std::sin(ph), co};
                    double h[3] = {wi[0] + wo[0], wi[1] + wo[1], wi[2] + wo[2]};
                    const double len = std::sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
                    if (!(len > 0)) continue;
                    for (double& x : h) x /= len;
                    const double ih = wi[0] * h[0] + wi[2] * h[2];
                    const double f = fresnel(ih, eta) * d.D(h[2]) * d.G1(mu, ih) * d.G1(co, ih) / (4.0 * mu);
                    sum += 2.0 * f * so * wth * wph;
                }
        }
    return sum;
}

/// Mitsuba 3's R_int from the independent R: 2 · mean over μ_k = max(10⁻⁶, k/63) of R(1/η) μ_k.
double internalReflectanceOverOutgoing(const Distribution& d, double eta, int panels) {
    double s = 0;
    for (int k = 0; k < 64; ++k) {
        const double mu = std::max(1e-6, k / 63.0);
        s += reflectanceOverOutgoing(d, 1.0 / eta, mu, panels) * mu;
    }
    return 2.0 * s / 64.0;
}

MicrofacetType typeOf(const Distribution& d) { return d.ggx ? MicrofacetType::GGX : MicrofacetType::Beckmann; }

}  // namespace

TEST(RoughPlasticMitsuba3, ReflectanceIntegralMatchesOutgoingQuadrature) {
    // roughReflectanceIntegral integrates over microfacet normals; here over outgoing directions
    // (converged to 1e-6). From inside (η < 1) the m-space rule converges slowly at the critical
    // angle: 48 points leave ≤ 4e-4 (q = 96: 1e-4); Mitsuba 3's R_int averages these errors out.
    for (const Distribution d : {Distribution{true, 0.4}, Distribution{true, 1.0}, Distribution{false, 0.3}})
        for (double eta : {kBk7, 1.0 / kBk7})
            for (double mu : {0.15, 0.5, 0.9}) {
                const double ref = reflectanceOverOutgoing(d, eta, mu);
                const double got = roughReflectanceIntegral(typeOf(d), eta, d.alpha, mu, 48);
                EXPECT_NEAR(got, ref, 4e-4) << "ggx " << d.ggx << " alpha " << d.alpha << " eta " << eta << " mu " << mu;
            }
}

TEST(RoughPlasticMitsuba3, InternalReflectanceIsMitsuba3sNodeMean) {
    for (const Distribution d : {Distribution{true, 0.4}, Distribution{true, 1.0}}) {
        const double ref = internalReflectanceOverOutgoing(d, kBk7, 24);
        const double got = mitsuba3InternalReflectance(typeOf(d), kBk7, d.alpha);
        EXPECT_NEAR(got, ref, 3e-4) << "alpha " << d.alpha;
        // Mitsuba 0.6's Fdr = 1 − Td counts the interface's single-scattering loss as reflected.
        const double fdr06 = 1.0 - roughInternalDiffuseIntegral(typeOf(d), kBk7, d.alpha);
        EXPECT_LT(got, fdr06 - 0.02) << "alpha " << d.alpha;
    }
    // Smooth limit: the node mean of the exact smooth internal reflectance 2∫F(μ, 1/η) μ dμ.
    double smooth = 0;
    for (int k = 0; k < 64; ++k) {
        const double mu = std::max(1e-6, k / 63.0);
        smooth += fresnel(mu, 1.0 / kBk7) * mu;
    }
    EXPECT_NEAR(mitsuba3InternalReflectance(MicrofacetType::GGX, kBk7, 0.0), 2.0 * smooth / 64.0, 1e-6);
}

TEST(RoughPlasticMitsuba3, TexturedAlphaCurveMatchesDirectValues) {
    // A textured α (iris extension) reads R_int from a curve over the table's α nodes.
    const Mitsuba3InternalReflectanceCurve curve(MicrofacetType::GGX, float(kBk7));
    for (float alpha : {0.0f, 0.01f, 0.1f, 0.37f, 0.4f, 0.83f, 1.0f})
        EXPECT_NEAR(curve.at(alpha), mitsuba3InternalReflectance(MicrofacetType::GGX, kBk7, alpha), 2e-4) << alpha;
}

TEST(RoughPlasticMitsuba3, AlbedoUnderUniformLightMatchesModel) {
    // Directional albedo of a version 3 roughplastic (white furnace: sample() weights) against
    // Mitsuba 3's formula integrated independently: R(η, α, μo) + ρ/(1 − R_int) T(μo) Td, with
    // R and R_int over outgoing directions, T and Td by brute-force quadrature. Before the version
    // split (Fdr = 1 − Td everywhere) the diffuse part was 31 % (α 0.4) / 70 % (α 1) too bright.
    const double rho = 0.5;
    for (const Distribution d : {Distribution{true, 0.4}, Distribution{true, 1.0}}) {
        const double rInt = internalReflectanceOverOutgoing(d, kBk7, 16);
        const double td = roughInternalDiffuseIntegral(typeOf(d), kBk7, d.alpha);
        for (bool specular : {false, true}) {
            auto inst = makeBSDFVersion(3, "roughplastic",
                                        {{"distribution", std::string("ggx")},
                                         {"alpha", float(d.alpha)},
                                         {"int_ior", float(kBk7)},
                                         {"ext_ior", 1.0f},
                                         {"specular_reflectance", specular ? 1.0f : 0.0f},
                                         {"diffuse_reflectance", float(rho)}});
            for (float c : {0.3f, 0.8f}) {
                const auto a = albedo(*inst.bsdf, dirFromCos(c), 200000);
                const double tO = roughTransmittanceIntegral(typeOf(d), kBk7, d.alpha, c);
                const double expected = (specular ? reflectanceOverOutgoing(d, kBk7, c) : 0.0) + rho / (1.0 - rInt) * tO * td;
                EXPECT_NEAR(a[0].mean, expected, 5 * a[0].stderr_ + 2e-3)
                    << "alpha " << d.alpha << " specular " << specular << " cos " << c;
            }
        }
    }
}

TEST(RoughPlasticMitsuba3, SceneVersionChoosesTheModel) {
    // The same roughplastic in a version 0.6, 2.0 and 3.0 file: the diffuse term (ks = 0) is
    // ρ/(1 − Fdr) T12 T21/(π η²) with Fdr = 1 − Td (0.6) or Mitsuba 3's R_int (2.x, 3.x).
    auto parse = [](const std::string& version) {
        const std::string xml = "<scene version=\"" + version +
                                "\"><bsdf type=\"roughplastic\" id=\"p\">"
                                "<string name=\"distribution\" value=\"ggx\"/><float name=\"alpha\" value=\"0.4\"/>"
                                "<float name=\"int_ior\" value=\"1.5\"/><float name=\"ext_ior\" value=\"1\"/>"
                                "<float name=\"specular_reflectance\" value=\"0\"/>"
                                "<rgb name=\"diffuse_reflectance\" value=\"0.2, 0.5, 0.8\"/>"
                                "<boolean name=\"nonlinear\" value=\"true\"/></bsdf></scene>";
        ParsedScene s = parseSceneString(xml, ".");
        upgradeScene(s);  // as the loader reads it: the version's convention
        EXPECT_EQ(s.objects.size(), 3u);  // the bsdf, and the default sensor and integrator
        return makeBSDF(*s.objects.at(0), SampledWavelengths::rgb(defaultChannelWavelengths()));
    };
    const RoughTransmittanceTables& t = roughPlasticTables(MicrofacetType::GGX);
    const float fdr06 = 1.0f - t.internalDiffuseTransmittance(1.5f, 0.4f);
    const float rInt = float(mitsuba3InternalReflectance(MicrofacetType::GGX, 1.5, 0.4));
    const vec3 wo = dirFromCos(0.6f, 0.2f), wi = dirFromCos(0.9f, 2.5f);
    const double tt = double(t.transmittance(1.5f, 0.4f, wi.z)) * t.transmittance(1.5f, 0.4f, wo.z) / (M_PI * 2.25);
    const float rho[3] = {0.2f, 0.5f, 0.8f};
    for (const char* version : {"0.6.0", "2.0.0", "3.0.0"}) {
        const BSDFInstance inst = parse(version);
        const float fdr = version[0] == '0' ? fdr06 : rInt;
        const SampledSpectrum f = inst.bsdf->eval(wo, wi, TransportMode::Radiance);
        for (int c = 0; c < 3; ++c) {
            const double expected = rho[c] / (1.0 - rho[c] * fdr) * tt;  // nonlinear
            EXPECT_NEAR(f[c], expected, 1e-5 * expected) << version << " channel " << c;
        }
    }
    EXPECT_LT(rInt, fdr06 - 0.05f);  // the versions really differ here
}
