// RGB mode renders a Mitsuba scene's tabulated spectra with the RGB values Mitsuba's RGB variant
// computes (spectral/mitsuba_rgb.h, issue 14): named conductors (`material`), conductor eta/k given
// as spectra, λ:value reflectances and emissions, chosen by the scene's version. Each expected
// value is the published formula evaluated here on its own (plain loops over the CIE data iris
// has), not by the code under test.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/properties.h"
#include "spectral/cie.h"
#include "spectral/conductor_presets.h"
#include "spectral/ior_params.h"
#include "spectral/mitsuba_rgb.h"
#include "spectral/piecewise_linear_spectrum.h"
#include "spectral/spectrum_params.h"
#include "render/loader/scene_upgrade.h"
#include "spectral/wavelengths.h"
#include "tests/support/bsdf_test_util.h"
#include "tests/support/spectrum_pairs.h"

using namespace iris;
using iris::test::spectrumPairs;

namespace {

const SampledWavelengths kRGB = SampledWavelengths::rgb(defaultChannelWavelengths());

struct Table {
    std::vector<float> l, v;
};

double tableAt(const Table& t, double w) {  // linear interpolant inside the table
    for (size_t i = 0; i + 1 < t.l.size(); ++i)
        if (w >= t.l[i] && w <= t.l[i + 1]) return t.v[i] + (t.v[i + 1] - t.v[i]) * (w - t.l[i]) / (t.l[i + 1] - t.l[i]);
    return 0.0;
}

dvec3 mitsubaMatrix(const dvec3& c) {  // Mitsuba 0.6 and 3, xyz_to_srgb / Spectrum::fromXYZ
    return {3.240479 * c.x - 1.537150 * c.y - 0.498535 * c.z, -0.969256 * c.x + 1.875991 * c.y + 0.041556 * c.z,
            0.055648 * c.x - 0.204043 * c.y + 1.057311 * c.z};
}

// Mitsuba 3, spectrum_list_to_srgb with the values scaled by MI_CIE_Y_NORMALIZATION: 1000 points
// w_i = 360 + 470 i/999, the CIE curves and D65 tabulated at 5 nm and interpolated linearly.
vec3 mitsuba3Reference(const Table& t, bool d65, bool bounded) {
    const auto node5 = [](double w, auto f) {
        const int i = std::min(int((w - 360.0) / 5.0), 93);
        const double a = 360.0 + 5.0 * i, u = (w - a) / 5.0;
        return f(float(a)) * (1.0 - u) + f(float(a + 5.0)) * u;
    };
    dvec3 xyz(0.0);
    for (int i = 0; i < 1000; ++i) {
        const double w = 360.0 + 470.0 * i / 999.0;
        if (w < t.l.front() || w > t.l.back()) continue;
        const dvec3 cmf = node5(w, [](float l) { return dvec3(cie::xyzBar(l)); });
        const double illum = d65 ? node5(w, [](float l) { return double(cie::d65(l)); }) / 98.99741751876255 : 1.0;
        xyz += cmf * tableAt(t, w) * illum;
    }
    dvec3 rgb = mitsubaMatrix(xyz * 0.47 / 106.7502593994140625);
    for (int c = 0; c < 3; ++c) rgb[c] = bounded ? std::clamp(rgb[c], 0.0, 1.0) : std::max(rgb[c], 0.0);
    return vec3(rgb);
}

// Mitsuba 0.6, Spectrum::fromContinuousSpectrum: ∫ S cmf / ∫ ȳ over 360–830 nm, here by the
// midpoint rule on a 0.01 nm grid (the 1 nm CIE table interpolated linearly, S zero outside).
vec3 mitsuba06Reference(const Table& t) {
    dvec3 xyz(0.0);
    double y = 0.0;
    constexpr double h = 0.01;
    for (double w = 360.0 + h / 2; w < 830.0; w += h) {
        const dvec3 cmf(cie::xyzBar(float(std::floor(w))) * float(1.0 - (w - std::floor(w))) +
                        cie::xyzBar(float(std::floor(w) + 1.0)) * float(w - std::floor(w)));
        xyz += cmf * tableAt(t, w) * h;
        y += cmf.y * h;
    }
    return vec3(mitsubaMatrix(xyz / y));
}

Properties props(const std::string& tag, const std::string& type, int version) {
    Properties p(tag, type, SourceLocation{"scene.xml", 3});
    p.setFormatVersion(version);
    return p;
}


void expectNear(const SampledSpectrum& s, const vec3& want, float tol, const std::string& what) {
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(s[c], want[c], tol * std::max(1.0f, want[c])) << what << " channel " << c;
}

}  // namespace

namespace {

Table tableOf(const SpectrumPtr& s) {
    const auto* pl = dynamic_cast<const PiecewiseLinearSpectrum*>(s.get());
    EXPECT_NE(pl, nullptr);
    return pl ? Table{pl->lambdas(), pl->values()} : Table{};
}

ConductorIOR conductor(const char* material, int version) {
    Properties p = props("bsdf", "roughconductor", version);
    p.set("material", std::string(material), SourceLocation{"scene.xml", 4});
    // η and κ are divided by the exterior index (ext_ior, default 1; a version 0.x scene's gets
    // Mitsuba 0.6's extEta, default air 1.000277, from the upgrade pass): 1 here, so that the
    // tables' own projection is seen.
    p.set("ext_ior", 1.0f, SourceLocation{"scene.xml", 5});
    upgradeObject(p);  // as the loader reads it: the version's convention
    return readConductor(p);
}

}  // namespace

TEST(MitsubaRGB, NamedConductorIsMitsuba3Projection) {
    // a-C (test_textured_roughconductor): before, RGB mode used η, κ at 645/525/445 nm
    // (2.43, 2.31, 2.17); Mitsuba 3's scalar_rgb projects the tables without D65 (2.94, 2.23, 1.97).
    for (const char* name : {"a-C", "Ag", "Al", "Au", "Cu"}) {
        const ConductorSpectra tables = loadConductorPreset(name);
        for (int version : {2, 3}) {
            SampledSpectrum eta, k;
            conductor(name, version).sample(kRGB, &eta, &k);
            expectNear(eta, mitsuba3Reference(tableOf(tables.eta), false, false), 2e-5f, std::string(name) + " eta");
            expectNear(k, mitsuba3Reference(tableOf(tables.k), false, false), 2e-5f, std::string(name) + " k");
        }
    }
    // Ag as an independent implementation of the same formula (a script over the same tables) gives it.
    SampledSpectrum eta, k;
    conductor("Ag", 3).sample(kRGB, &eta, &k);
    expectNear(eta, vec3(0.155276f, 0.116728f, 0.138388f), 1e-4f, "Ag eta");
    expectNear(k, vec3(4.828354f, 3.122222f, 2.146901f), 1e-4f, "Ag k");
    // a-C, the values of the scene (the same script).
    conductor("a-C", 2).sample(kRGB, &eta, &k);
    expectNear(eta, vec3(2.9440f, 2.2271f, 1.9682f), 1e-4f, "a-C eta");
    expectNear(k, vec3(0.8875f, 0.7993f, 0.8153f), 1e-4f, "a-C k");
}

TEST(MitsubaRGB, NamedConductorVersion06IsExactProjection) {
    // Mitsuba 0.6 (version 0.x): fromContinuousSpectrum of the table, no D65, no zero extension.
    for (const char* name : {"a-C", "Au", "Cu"}) {
        const ConductorSpectra tables = loadConductorPreset(name);
        SampledSpectrum eta, k;
        conductor(name, 0).sample(kRGB, &eta, &k);
        expectNear(eta, mitsuba06Reference(tableOf(tables.eta)), 2e-5f, std::string(name) + " eta");
        expectNear(k, mitsuba06Reference(tableOf(tables.k)), 2e-5f, std::string(name) + " k");
    }
}

TEST(MitsubaRGB, SpectralModeKeepsTheTables) {
    const ConductorSpectra tables = loadConductorPreset("a-C");
    for (int version : {0, 3}) {
        const SampledWavelengths wl = SampledWavelengths::sampleVisible(0.37f, 8);
        SampledSpectrum eta, k;
        conductor("a-C", version).sample(wl, &eta, &k);
        for (int i = 0; i < wl.size(); ++i) {
            EXPECT_EQ(eta[i], tables.eta->eval(wl.lambda(i)));
            EXPECT_EQ(k[i], tables.k->eval(wl.lambda(i)));
        }
    }
}

TEST(MitsubaRGB, SceneTablesFollowTheVersion) {
    // fragments/single_sphere.xml: the area light's radiance and the light's reflectance.
    const SpectrumValue radiance = spectrumPairs({400, 500, 600, 700}, {0, 8, 15.6f, 18.4f});
    const SpectrumValue reflectance = spectrumPairs({400, 500, 600, 700}, {0.78f, 0.78f, 0.78f, 0.78f});
    const SpectrumValue eta = spectrumPairs({400, 550, 700}, {1.9f, 2.2f, 2.6f});
    const Table tRadiance{radiance.lambdas, radiance.values}, tReflectance{reflectance.lambdas, reflectance.values},
        tEta{eta.lambdas, eta.values};
    for (int version : {0, 2, 3}) {
        Properties emitter = props("emitter", "area", version);
        emitter.set("radiance", radiance, SourceLocation{"scene.xml", 5});
        Properties bsdf = props("bsdf", "diffuse", version);
        bsdf.set("reflectance", reflectance, SourceLocation{"scene.xml", 6});
        upgradeObject(emitter);  // as the loader reads them: the version's convention
        upgradeObject(bsdf);
        const SampledSpectrum L = getSpectrum(emitter, "radiance", SpectrumKind::Illuminant)->sample(kRGB);
        const SampledSpectrum rho = getSpectrum(bsdf, "reflectance", SpectrumKind::Reflectance)->sample(kRGB);
        Properties cond = props("bsdf", "conductor", version);
        cond.set("eta", eta, SourceLocation{"scene.xml", 7});
        cond.set("k", 1.0f, SourceLocation{"scene.xml", 8});
        upgradeObject(cond);
        const IOR etaIOR = readIOR(cond, "eta", IOR(), IorQuantity::ConductorOptics);
        const SampledSpectrum etaRGB = etaIOR.sample(kRGB);
        const std::string v = " (version " + std::to_string(version) + ")";
        if (version >= 2) {
            // Mitsuba 3: emission not weighted; reflectance D65 weighted and clipped to [0, 1];
            // an unbounded table (eta) D65 weighted.
            expectNear(L, mitsuba3Reference(tRadiance, false, false), 2e-5f, "radiance" + v);
            expectNear(rho, mitsuba3Reference(tReflectance, true, true), 2e-5f, "reflectance" + v);
            expectNear(etaRGB, mitsuba3Reference(tEta, true, false), 2e-5f, "eta" + v);
        } else {
            // Mitsuba 0.6: zero-extended by one mean spacing, projected without D65, clamped at 0.
            const auto extended = [](Table t) {
                const float d = (t.l.back() - t.l.front()) / float(t.l.size() - 1);
                if (t.v.front() != 0) t.l.insert(t.l.begin(), t.l.front() - d), t.v.insert(t.v.begin(), 0.0f);
                if (t.v.back() != 0) t.l.push_back(t.l.back() + d), t.v.push_back(0.0f);
                return t;
            };
            const auto clamped = [](vec3 c) { return glm::max(c, vec3(0.0f)); };
            expectNear(L, clamped(mitsuba06Reference(extended(tRadiance))), 2e-5f, "radiance" + v);
            expectNear(rho, clamped(mitsuba06Reference(extended(tReflectance))), 2e-5f, "reflectance" + v);
            expectNear(etaRGB, clamped(mitsuba06Reference(extended(tEta))), 2e-5f, "eta" + v);
        }
        // Spectral mode evaluates the tables as before.
        const SampledWavelengths wl = SampledWavelengths::sampleVisible(0.61f, 4);
        const SampledSpectrum Ls = getSpectrum(emitter, "radiance", SpectrumKind::Illuminant)->sample(wl);
        for (int i = 0; i < wl.size(); ++i) EXPECT_FLOAT_EQ(Ls[i], float(tableAt(tRadiance, wl.lambda(i))));
    }
}

TEST(MitsubaRGB, Mitsuba3WhiteIsNearlyOne) {
    // The D65-weighted projection of reflectance 1 is Mitsuba's white, 0.9989 (its two constants
    // normalise a flat spectrum and D65 separately); the unweighted one of radiance 1 is the sRGB
    // colour of the equal-energy spectrum, (1.205, 0.948, 0.909).
    const vec3 white = mitsuba3SpectrumToRGB({360, 830}, {1, 1}, true, true);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(white[c], 0.9989f, 3e-4f);
    const vec3 e = mitsuba3SpectrumToRGB({360, 830}, {1, 1}, false, false);
    EXPECT_NEAR(e.x, 1.2049f, 2e-4f);
    EXPECT_NEAR(e.y, 0.9482f, 2e-4f);
    EXPECT_NEAR(e.z, 0.9093f, 2e-4f);
}

TEST(MitsubaRGB, SingleValuedEmissionFollowsTheVersion) {
    // <spectrum name="radiance" value="0.5"/>: Mitsuba 3 makes it the flat spectrum 0.5 (spectral)
    // and its sRGB colour 0.5 · M (1, 1, 1) (RGB); Mitsuba 0.6 (intent "illuminant") and a <float>
    // give 0.5 × D65 with Y = 1, white (0.5, 0.5, 0.5) in RGB mode.
    SpectrumValue half;
    half.constant = 0.5f;
    const SampledWavelengths wl = SampledWavelengths::sampleVisible(0.23f, 8);
    const SpectrumPtr d65 = spectrumFromNumber(0.5f, SpectrumKind::Illuminant);
    for (int version : {0, 2, 3}) {
        // As the loader gives it: a version 0.x scene's single value became a number in the
        // upgrade pass (render/loader/scene_upgrade.h).
        auto emitter = std::make_shared<Properties>(props("emitter", "area", version));
        emitter->set("radiance", half, SourceLocation{"scene.xml", 5});
        emitter->set("number", 0.5f, SourceLocation{"scene.xml", 6});
        test::asSceneVersion(emitter, version);
        const SpectrumPtr s = getSpectrum(*emitter, "radiance", SpectrumKind::Illuminant);
        const SpectrumPtr f = getSpectrum(*emitter, "number", SpectrumKind::Illuminant);
        const SampledSpectrum spectral = s->sample(wl), fromFloat = f->sample(wl), rgb = s->sample(kRGB);
        for (int i = 0; i < wl.size(); ++i) {
            EXPECT_EQ(fromFloat[i], d65->eval(wl.lambda(i)));  // a number: × D65 in every version
            EXPECT_EQ(spectral[i], version >= 2 ? 0.5f : d65->eval(wl.lambda(i))) << "version " << version;
        }
        const vec3 want = version >= 2 ? vec3(0.5 * mitsubaMatrix(dvec3(1.0))) : vec3(0.5f);
        expectNear(rgb, want, 1e-3f, "rgb, version " + std::to_string(version));
        if (version >= 2) EXPECT_NEAR(rgb[0], 0.5f * 1.2048f, 1e-4f);
        // A reflectance's single value is the constant in every version.
        auto bsdf = std::make_shared<Properties>(props("bsdf", "diffuse", version));
        bsdf->set("reflectance", half, SourceLocation{"scene.xml", 7});
        test::asSceneVersion(bsdf, version);
        const SampledSpectrum rho = getSpectrum(*bsdf, "reflectance", SpectrumKind::Reflectance)->sample(wl);
        for (int i = 0; i < wl.size(); ++i) EXPECT_EQ(rho[i], 0.5f);
    }
}
