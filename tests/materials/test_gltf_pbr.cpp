// The glTF 2.0 material (`gltf_pbr`) against the formulas of glTF 2.0 Appendix B and of the
// KHR_materials_* extensions, written out here independently of materials/gltf_pbr_terms, plus
// chi-square sampling tests, eval/sample/pdf consistency, white furnaces and the two thin-film
// readings (exact per wavelength; KHR_materials_iridescence's RGB approximation).
#include <cmath>

#include <gtest/gtest.h>

#include "core/error.h"
#include "materials/gltf_pbr_terms.h"
#include "spectral/thin_film_cycles.h"
#include "spectral/thin_film_industry.h"
#include "tests/support/bsdf_test_util.h"

namespace iris {
namespace {

using test::makeBSDF;
using test::Param;

// Appendix B.3.2, as printed: D = α² χ⁺(n·h) / (π ((n·h)²(α² − 1) + 1)²);
// V = G / (4 |n·l| |n·v|), G = G1(l) G1(v), G1(x) = 2 |n·x| / (|n·x| + sqrt(α² + (1 − α²)(n·x)²)).
double specD(double a, double nh) { return a * a / (M_PI * std::pow(nh * nh * (a * a - 1) + 1, 2)); }  // in double: no cancellation
double specG1(double a, double nx) { return 2 * nx / (nx + std::sqrt(a * a + (1 - a * a) * nx * nx)); }
double specV(double a, double nl, double nv) { return specG1(a, nl) * specG1(a, nv) / (4 * nl * nv); }

struct Pair {
    vec3 wo, wi, h;
    double vh;
};
Pair pairAt(float cosO, float cosI, float phi) {
    Pair p{test::dirFromCos(cosO), test::dirFromCos(cosI, phi), {}, 0};
    p.h = glm::normalize(p.wo + p.wi);
    p.vh = glm::dot(p.wo, p.h);
    return p;
}

const Pair kPairs[] = {pairAt(0.9f, 0.7f, 2.0f), pairAt(0.5f, 0.8f, 3.0f), pairAt(0.3f, 0.4f, 1.0f)};

TEST(GltfPbr, MetalIsSchlickTimesSpecularBrdf) {
    const vec3 C(0.9f, 0.6f, 0.2f);
    const double rough = 0.5, a = rough * rough;
    auto inst = makeBSDF("gltf_pbr", {{"base_color", RGBValue{C}}, {"metallic", 1.0f}, {"roughness", float(rough)}});
    for (const Pair& p : kPairs) {
        const SampledSpectrum f = inst.bsdf->eval(p.wo, p.wi, TransportMode::Radiance);
        const double dv = specD(a, p.h.z) * specV(a, p.wi.z, p.wo.z);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(f[c], (C[c] + (1 - C[c]) * std::pow(1 - p.vh, 5)) * dv, 2e-5 * f[c] + 1e-7) << c;
    }
}

TEST(GltfPbr, DielectricIsFresnelMixOfDiffuseAndSpecular) {
    // KHR_materials_ior and _specular: f0 = ((ior − 1)/(ior + 1))² · specularColor, fr Schlick,
    // f = (1 − s·max(fr))·C/π + s·fr·D·V.
    const vec3 C(0.2f, 0.5f, 0.8f), sc(1.0f, 0.5f, 0.25f);
    const double ior = 1.8, s = 0.7, a = 0.3 * 0.3;
    auto inst = makeBSDF("gltf_pbr", {{"base_color", RGBValue{C}}, {"metallic", 0.0f}, {"roughness", 0.3f}, {"ior", float(ior)},
                                       {"specular", float(s)}, {"specular_color", RGBValue{sc}}});
    const double f0 = std::pow((ior - 1) / (ior + 1), 2);
    for (const Pair& p : kPairs) {
        const SampledSpectrum f = inst.bsdf->eval(p.wo, p.wi, TransportMode::Radiance);
        double fr[3], frMax = 0;
        for (int c = 0; c < 3; ++c) frMax = std::max(frMax, fr[c] = f0 * sc[c] + (1 - f0 * sc[c]) * std::pow(1 - p.vh, 5));
        const double dv = specD(a, p.h.z) * specV(a, p.wi.z, p.wo.z);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(f[c], (1 - s * frMax) * C[c] / M_PI + s * fr[c] * dv, 2e-5 * f[c]) << c;
    }
}

TEST(GltfPbr, ClearcoatLayersByItsFresnel) {
    const float cc = 0.8f, ccr = 0.2f;
    auto base = makeBSDF("gltf_pbr", {{"metallic", 0.0f}, {"roughness", 0.6f}});
    auto coated = makeBSDF("gltf_pbr", {{"metallic", 0.0f}, {"roughness", 0.6f}, {"clearcoat", cc}, {"clearcoat_roughness", ccr}});
    for (const Pair& p : kPairs) {
        const double Fc = 0.04 + 0.96 * std::pow(1 - p.vh, 5);  // KHR_materials_clearcoat: ior 1.5
        const double coat = specD(ccr * ccr, p.h.z) * specV(ccr * ccr, p.wi.z, p.wo.z);
        const SampledSpectrum fb = base.bsdf->eval(p.wo, p.wi, TransportMode::Radiance);
        const SampledSpectrum fc = coated.bsdf->eval(p.wo, p.wi, TransportMode::Radiance);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(fc[c], (1 - cc * Fc) * fb[c] + cc * Fc * coat, 2e-5 * fc[c]);
    }
}

TEST(GltfPbr, SheenAddsCharlieAndScalesTheBaseByItsAlbedo) {
    const vec3 sheen(0.9f, 0.4f, 0.6f);
    const float sr = 0.5f;
    auto base = makeBSDF("gltf_pbr", {{"metallic", 0.0f}, {"roughness", 0.6f}});
    auto sheened = makeBSDF("gltf_pbr", {{"metallic", 0.0f}, {"roughness", 0.6f}, {"sheen_color", RGBValue{sheen}}, {"sheen_roughness", sr}});
    for (const Pair& p : kPairs) {
        const float maxS = 0.9f;
        const double scale = std::min(1 - maxS * gltf::sheenAlbedo(p.wo.z, sr), 1 - maxS * gltf::sheenAlbedo(p.wi.z, sr));
        const double lobe = gltf::charlieD(sr * sr, p.h.z) * gltf::charlieV(sr * sr, p.wi.z, p.wo.z);
        const SampledSpectrum fb = base.bsdf->eval(p.wo, p.wi, TransportMode::Radiance);
        const SampledSpectrum fs = sheened.bsdf->eval(p.wo, p.wi, TransportMode::Radiance);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(fs[c], sheen[c] * lobe + fb[c] * scale, 2e-5 * fs[c]);
    }
}

TEST(GltfPbr, SheenAlbedoTableIsTheLobesDirectionalAlbedo) {
    // A black base with white sheen: the BSDF is the Charlie lobe alone, whose Monte Carlo albedo
    // must equal the table's E(cosθ) within its standard error (plus the table's interpolation).
    for (float sr : {0.3f, 0.7f})
        for (float cosO : {0.9f, 0.5f, 0.2f}) {
            auto inst = makeBSDF("gltf_pbr", {{"base_color", RGBValue{vec3(0.0f)}}, {"metallic", 0.0f}, {"specular", 0.0f},
                                               {"sheen_color", RGBValue{vec3(1.0f)}}, {"sheen_roughness", sr}});
            // The base is scaled to 0 × (1 − E): only the lobe remains.
            const auto a = test::albedo(*inst.bsdf, test::dirFromCos(cosO), 400000, 11);
            EXPECT_NEAR(a[0].mean, gltf::sheenAlbedo(cosO, sr), 4 * a[0].stderr_ + 0.01) << sr << " " << cosO;
        }
}

TEST(GltfPbr, ThinFilmOfZeroThicknessGivesTheExactBareBaseFresnel) {
    // Exact reading (RGB mode, channel wavelengths): with i = 1, F = R_film, which at d = 0 is the
    // bare base's Fresnel reflectance (not Schlick's): dielectric of index ior.
    auto inst = makeBSDF("gltf_pbr", {{"base_color", RGBValue{vec3(0.0f)}}, {"metallic", 0.0f}, {"roughness", 0.3f}, {"ior", 1.5f},
                                       {"iridescence", 1.0f}, {"iridescence_thickness", 0.0f}, {"iridescence_ior", 1.8f}});
    for (const Pair& p : kPairs) {
        const double F = fresnelInterfaceRT(p.vh, 1.0, complexd(1.5, 0.0)).R();
        const double dv = specD(0.09, p.h.z) * specV(0.09, p.wi.z, p.wo.z);
        const SampledSpectrum f = inst.bsdf->eval(p.wo, p.wi, TransportMode::Radiance);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(f[c], F * dv, 1e-4 * f[c]) << c;
    }
}

TEST(GltfPbr, KhrReadingIsTheReadmesIridescentFresnel) {
    // rgb_mode khr_iridescence, metallic base: F = iridescent_fresnel(1, ior_film, baseColor, d, v·h).
    const vec3 C(0.95f, 0.64f, 0.54f);
    auto khr = makeBSDF("gltf_pbr", {{"base_color", RGBValue{C}}, {"metallic", 1.0f}, {"roughness", 0.4f}, {"iridescence", 1.0f},
                                      {"iridescence_thickness", 400.0f}, {"iridescence_ior", 1.5f}, {"rgb_mode", std::string("khr_iridescence")}});
    auto exact = makeBSDF("gltf_pbr", {{"base_color", RGBValue{C}}, {"metallic", 1.0f}, {"roughness", 0.4f}, {"iridescence", 1.0f},
                                        {"iridescence_thickness", 400.0f}, {"iridescence_ior", 1.5f}});
    double differs = 0;
    for (const Pair& p : kPairs) {
        const dvec3 F = khrIridescentFresnel(1.0, 1.5, dvec3(C), 400.0, p.vh);
        const double dv = specD(0.16, p.h.z) * specV(0.16, p.wi.z, p.wo.z);
        const SampledSpectrum f = khr.bsdf->eval(p.wo, p.wi, TransportMode::Radiance);
        const SampledSpectrum fe = exact.bsdf->eval(p.wo, p.wi, TransportMode::Radiance);
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(f[c], F[c] * dv, 2e-5 * f[c]) << c;
            differs = std::max(differs, std::abs(double(fe[c]) - f[c]) / f[c]);
        }
    }
    EXPECT_GT(differs, 0.01) << "the two readings must differ (else the mode is not switched)";
}

TEST(GltfPbr, Cycles42ReadingIsBlendersFilmOnDielectricsAndNoneOnMetals) {
    // rgb_mode cycles_4_2: the dielectric base's film is cyclesThinFilmRGB(1, ior_film, ior_base, v·h, d)
    // (ior_base from F0 = ((ior − 1)/(ior + 1))², specular 1, white specular colour: the ior itself);
    // Cycles 4.2 has no film on metals, so a metal keeps its Schlick term B.3.4.
    const vec3 C(0.95f, 0.64f, 0.54f);
    const double ior = 1.5, d = 400.0, filmIor = 1.3;
    auto film = [&](float metallic, const char* mode) {
        return makeBSDF("gltf_pbr", {{"base_color", RGBValue{C}}, {"metallic", metallic}, {"roughness", 0.4f}, {"ior", float(ior)},
                                     {"iridescence", 1.0f}, {"iridescence_thickness", float(d)}, {"iridescence_ior", float(filmIor)},
                                     {"rgb_mode", std::string(mode)}},
                        SampledWavelengths::rgb(defaultChannelWavelengths()));
    };
    auto dielectric = film(0.0f, "cycles_4_2"), metal = film(1.0f, "cycles_4_2"), exact = film(0.0f, "point");
    double differs = 0;
    for (const Pair& p : kPairs) {
        const double dv = specD(0.16, p.h.z) * specV(0.16, p.wi.z, p.wo.z);
        const dvec3 F = cyclesThinFilmRGB(1.0, filmIor, ior, p.vh, d);
        const SampledSpectrum fm = metal.bsdf->eval(p.wo, p.wi, TransportMode::Radiance);
        const SampledSpectrum fd = dielectric.bsdf->eval(p.wo, p.wi, TransportMode::Radiance);
        const SampledSpectrum fe = exact.bsdf->eval(p.wo, p.wi, TransportMode::Radiance);
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(fm[c], (C[c] + (1 - C[c]) * std::pow(1 - p.vh, 5)) * dv, 2e-5 * fm[c] + 1e-7) << c;
            // The specular part is F·D·V; the diffuse part (1 − F)·C/π is checked by the furnace tests.
            const double diffuse = (1 - F[c]) * C[c] / M_PI;
            EXPECT_NEAR(fd[c], F[c] * dv + diffuse, 2e-4 * fd[c]) << c;
            differs = std::max(differs, std::abs(double(fe[c]) - fd[c]) / fd[c]);
        }
    }
    EXPECT_GT(differs, 0.01) << "the Cycles and the exact readings must differ (else the mode is not switched)";
}

TEST(GltfPbr, BackFacesAreMirroredOrCulled) {
    // §3.9.5: a double-sided material is lit from behind as from the front; a single-sided one is
    // culled there (light passes through it unchanged, weight 1).
    auto two = makeBSDF("gltf_pbr", {{"metallic", 0.0f}, {"roughness", 0.4f}, {"double_sided", true}});
    auto one = makeBSDF("gltf_pbr", {{"metallic", 0.0f}, {"roughness", 0.4f}, {"double_sided", false}});
    for (const Pair& p : kPairs) {
        const SampledSpectrum front = two.bsdf->eval(p.wo, p.wi, TransportMode::Radiance);
        const SampledSpectrum back = two.bsdf->eval(-p.wo, -p.wi, TransportMode::Radiance);
        for (int c = 0; c < 3; ++c) EXPECT_EQ(front[c], back[c]);
        EXPECT_EQ(two.bsdf->pdf(p.wo, p.wi, TransportMode::Radiance), two.bsdf->pdf(-p.wo, -p.wi, TransportMode::Radiance));
        EXPECT_EQ(one.bsdf->eval(-p.wo, -p.wi, TransportMode::Radiance)[0], 0.0f);
        const auto s = one.bsdf->sample(-p.wo, 0.3f, vec2(0.4f, 0.6f), TransportMode::Radiance);
        ASSERT_TRUE(s.has_value());
        EXPECT_TRUE(s->isNull());
        EXPECT_EQ(s->wi, p.wo);
        EXPECT_FLOAT_EQ(s->weight()[0], 1.0f);
        const auto m = two.bsdf->sample(-p.wo, 0.3f, vec2(0.4f, 0.6f), TransportMode::Radiance);
        ASSERT_TRUE(m.has_value());
        EXPECT_LT(m->wi.z, 0.0f) << "a mirrored reflection stays on the back side";
    }
}

// KHR_materials_volume's refractive BTDF (README "Implementation"; Walter et al. 2007 eq. 21 with
// the viewer's index as η_o), written out here in double from the README's terms: smooth-ish GGX,
// white base, transmission 1, ior 1.5.
TEST(GltfPbr, VolumeBoundaryRefractsWithTheReadmesBtdf) {
    const double ior = 1.5, a = 0.3 * 0.3;
    auto vol = makeBSDF("gltf_pbr", {{"base_color", RGBValue{vec3(1.0f)}}, {"metallic", 0.0f}, {"roughness", 0.3f},
                                     {"transmission", 1.0f}, {"thickness", 1.0f}, {"specular", 1.0f}},
                        SampledWavelengths::rgb(defaultChannelWavelengths()));
    const double f0 = std::pow((ior - 1) / (ior + 1), 2);
    for (bool inside : {false, true}) {
        const double eta = inside ? 1 / ior : ior;  // beyond the surface / viewer's side
        // Pairs near the smooth refraction (sin θt = sin θv / eta), so that h sees both sides.
        const vec3 wo = inside ? -test::dirFromCos(0.9f, 0.3f) : test::dirFromCos(0.8f, 0.3f);
        const vec3 wi = inside ? test::dirFromCos(0.75f, 0.5f) : -test::dirFromCos(0.9f, 0.5f);
        // Mirror to the front (as the BSDF does from inside), then the README's H_TR.
        const glm::dvec3 v = inside ? -glm::dvec3(wo) : glm::dvec3(wo), l = inside ? -glm::dvec3(wi) : glm::dvec3(wi);
        glm::dvec3 h = glm::normalize(v + eta * l);
        if (h.z < 0) h = -h;
        const double vh = glm::dot(v, h), lh = glm::dot(l, h);
        ASSERT_TRUE(vh > 0 && lh < 0) << "not a refraction pair";
        // README cases: entering the denser side, Schlick at v·h; leaving it, at the transmitted angle.
        double cosF = vh;
        if (eta < 1) cosF = std::sqrt(1 - (1 - vh * vh) / (eta * eta));
        const double F = f0 + (1 - f0) * std::pow(1 - cosF, 5);
        const double G = specG1(a, std::abs(l.z)) * specG1(a, std::abs(v.z));
        const double btdf = std::abs(lh * vh) / std::abs(l.z * v.z) * G * specD(a, h.z) / std::pow(vh + eta * lh, 2);
        const double expect = (1 - F) * btdf;
        const float got = vol.bsdf->eval(wo, wi, TransportMode::Radiance)[1];
        EXPECT_NEAR(got, expect, 1e-4 * expect + 1e-6) << (inside ? "inside" : "outside");
        // The adjoint carries eta² (the README's formula, written with V on the incident side).
        EXPECT_NEAR(vol.bsdf->eval(wo, wi, TransportMode::Importance)[1], expect * eta * eta, 1e-4 * expect * eta * eta + 1e-6);
    }
    // Total internal reflection from inside: nothing leaves at 60° off the normal (sin θt = 1.3),
    // and the reflection's Fresnel is 1 (not scaled by KHR_materials_specular's factor).
    auto half = makeBSDF("gltf_pbr", {{"metallic", 0.0f}, {"roughness", 0.05f}, {"transmission", 1.0f}, {"thickness", 1.0f},
                                      {"specular", 0.5f}},
                         SampledWavelengths::rgb(defaultChannelWavelengths()));
    const vec3 wo = -test::dirFromCos(0.5f), wi = -test::dirFromCos(0.5f, kPi);  // mirror pair inside
    const vec3 out = test::dirFromCos(0.5f, kPi);
    EXPECT_EQ(half.bsdf->eval(wo, out, TransportMode::Radiance)[0], 0.0f);
    const double aa = 0.05 * 0.05;
    const double mirror = specV(aa, 0.5, 0.5) * specD(aa, 1.0);  // F = 1 at h = n
    EXPECT_NEAR(half.bsdf->eval(wo, wi, TransportMode::Radiance)[0], mirror, 1e-3 * mirror);
    // Thickness 0 is thin-walled: the transmitted direction is the mirror image of a reflection.
    auto thin = makeBSDF("gltf_pbr", {{"metallic", 0.0f}, {"roughness", 0.3f}, {"transmission", 1.0f}},
                         SampledWavelengths::rgb(defaultChannelWavelengths()));
    const auto s = thin.bsdf->sample(test::dirFromCos(0.6f), 0.9f, vec2(0.5f, 0.5f), TransportMode::Radiance);
    ASSERT_TRUE(s.has_value());
    EXPECT_EQ(s->eta, 1.0f) << "thin-walled: no index is crossed";
    EXPECT_THROW(makeBSDF("gltf_pbr", {{"thickness", -1.0f}}), Error);
}

TEST(GltfPbr, RejectsBadParameters) {
    EXPECT_THROW(makeBSDF("gltf_pbr", {{"metallic", 1.5f}}), Error);
    EXPECT_THROW(makeBSDF("gltf_pbr", {{"ior", 0.5f}}), Error);
    EXPECT_THROW(makeBSDF("gltf_pbr", {{"rgb_mode", std::string("cycles")}}), Error);
    EXPECT_THROW(makeBSDF("gltf_pbr", {{"iridescence_thickness", -1.0f}}), Error);
}

TEST(GltfPbrSampling, ChiSquareAndConsistency) {
    const std::vector<std::pair<std::string, std::vector<Param>>> cases = {
        {"dielectric", {{"base_color", RGBValue{vec3(0.6f, 0.4f, 0.2f)}}, {"metallic", 0.0f}, {"roughness", 0.4f}}},
        {"metal", {{"metallic", 1.0f}, {"roughness", 0.3f}}},
        {"transmission", {{"metallic", 0.0f}, {"roughness", 0.5f}, {"transmission", 0.7f}}},
        {"volume", {{"metallic", 0.0f}, {"roughness", 0.4f}, {"transmission", 0.8f}, {"thickness", 1.0f}, {"ior", 1.33f}}},
        {"layers", {{"metallic", 0.3f}, {"roughness", 0.5f}, {"clearcoat", 0.7f}, {"clearcoat_roughness", 0.2f},
                    {"sheen_color", RGBValue{vec3(0.5f)}}, {"sheen_roughness", 0.4f}, {"iridescence", 0.5f}}},
    };
    for (const auto& [name, params] : cases) {
        auto props = std::make_shared<Properties>("bsdf", "gltf_pbr", SourceLocation{});
        for (const Param& p : params) props->set(p.first, p.second, {});
        auto inst = test::makeBSDF(*props, SampledWavelengths::rgb(defaultChannelWavelengths()));
        for (float cosO : {0.8f, 0.3f, -0.7f}) {  // −0.7: from behind (inside a volume)
            test::Chi2Options opt;
            opt.numTests = int(cases.size()) * 2;
            const auto chi = test::chi2Test(*inst.bsdf, test::dirFromCos(cosO), opt);
            EXPECT_TRUE(chi.passed) << name << " cos " << cosO << ": " << chi.message;
            const auto cons = test::checkConsistency(*inst.bsdf, test::dirFromCos(cosO));
            EXPECT_EQ(cons.invalid, 0) << name << cons.message;
            EXPECT_LT(cons.maxRelErrF, 1e-4f) << name << cons.message;
            EXPECT_LT(cons.maxRelErrPdf, 1e-4f) << name << cons.message;
        }
    }
}

TEST(GltfPbrSampling, WhiteFurnace) {
    // Metals, thin-walled transmission and the layers reflect (and transmit) at most what arrives:
    // albedo ≤ 1 within 4σ. glTF's fresnel_mix weights a dielectric's base by 1 − F(v·h) per
    // direction pair rather than by the specular lobe's directional albedo, so a white dielectric
    // base may return slightly more than 1 (this test measured 1.024 at cosθ = 0.4, 1.062 under
    // sheen and clearcoat, 1.087 with an exact film whose per-wavelength 1 − F replaces the max):
    // those cases are held to 1.1.
    const std::vector<bool> strict = {false, true, true, false, false, true};
    const std::vector<std::vector<Param>> cases = {
        {{"base_color", RGBValue{vec3(1.0f)}}, {"metallic", 0.0f}, {"roughness", 0.5f}},
        {{"base_color", RGBValue{vec3(1.0f)}}, {"metallic", 1.0f}, {"roughness", 0.5f}},
        {{"base_color", RGBValue{vec3(1.0f)}}, {"metallic", 0.0f}, {"roughness", 0.5f}, {"transmission", 1.0f}},
        {{"base_color", RGBValue{vec3(1.0f)}}, {"metallic", 0.0f}, {"roughness", 0.5f}, {"sheen_color", RGBValue{vec3(1.0f)}},
         {"sheen_roughness", 0.5f}, {"clearcoat", 1.0f}},
        {{"base_color", RGBValue{vec3(1.0f)}}, {"metallic", 0.0f}, {"roughness", 0.3f}, {"iridescence", 1.0f}},
        {{"base_color", RGBValue{vec3(1.0f)}}, {"metallic", 0.0f}, {"roughness", 0.3f}, {"transmission", 1.0f}, {"thickness", 1.0f}},
    };
    int k = 0;
    for (const auto& params : cases) {
        auto props = std::make_shared<Properties>("bsdf", "gltf_pbr", SourceLocation{});
        for (const Param& p : params) props->set(p.first, p.second, {});
        auto inst = test::makeBSDF(*props, SampledWavelengths::rgb(defaultChannelWavelengths()));
        for (float cosO : {0.9f, 0.4f}) {
            const auto a = test::albedo(*inst.bsdf, test::dirFromCos(cosO), 200000, 20 + k);
            for (const auto& e : a) {
                EXPECT_TRUE(std::isfinite(e.mean)) << "case " << k;
                EXPECT_LE(e.mean, (strict[size_t(k)] ? 1.0 : 1.1) + 4 * e.stderr_) << "case " << k << " cos " << cosO;
            }
        }
        ++k;
    }
}

}  // namespace
}  // namespace iris
