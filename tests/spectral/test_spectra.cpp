// Spectrum classes: blackbody (Planck), piecewise-linear, D65, .spd files, and the RGB-mode values
// of spectrally defined spectra.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/error.h"
#include "core/properties.h"
#include "core/source_tree.h"
#include "spectral/blackbody_spectrum.h"
#include "spectral/color_space.h"
#include "spectral/piecewise_linear_spectrum.h"
#include "spectral/rgb_spectrum.h"
#include "spectral/spectrum_factory.h"
#include "spectral/spectrum_params.h"
#include "spectral/xyz.h"
#include "tests/support/error_of.h"

using namespace iris;
using iris::test::errorOf;
namespace fs = std::filesystem;

namespace {
float maxAbsDiff(const vec3& a, const vec3& b) {
    const vec3 d = glm::abs(a - b);
    return std::max({d.x, d.y, d.z});
}

// A fresh temporary directory per test binary run.
fs::path tempDir() {
    static const fs::path dir = [] {
        fs::path d = fs::temp_directory_path() / ("iris_test_spectra_" + std::to_string(::getpid()));
        fs::create_directories(d);
        return d;
    }();
    return dir;
}

std::string writeFile(const std::string& name, const std::string& text) {
    const fs::path p = tempDir() / name;
    std::ofstream(p) << text;
    return p.string();
}

}  // namespace

TEST(Spectra, BlackbodyStefanBoltzmannAndWien) {
    // ∫ B(λ, T) dλ = σ T⁴ / π (σ = 5.670374419e-8 W m⁻² K⁻⁴, CODATA 2018); midpoint rule in nm.
    const double sigma = 5.670374419e-8;
    for (double T : {1500.0, 5000.0}) {
        double integral = 0;  // W sr⁻¹ m⁻²
        const double h = 0.5;
        for (double l = 10.0 + 0.5 * h; l < 200000.0; l += h) integral += planck(l, T) * h * 1e-9;
        EXPECT_NEAR(integral / (sigma * T * T * T * T / kPi), 1.0, 1e-4) << T;
    }
    // Wien's displacement law, b = 2.897771955e-3 m K (CODATA 2018): the normalised peak is 1 there.
    const float T = 5000.0f, scale = 2.5f;
    const BlackbodySpectrum bb(T, scale);
    const float peak = float(2.897771955e-3 / T * 1e9);
    EXPECT_NEAR(bb.eval(peak), scale, 1e-5f * scale);
    EXPECT_LT(bb.eval(peak - 5.0f), bb.eval(peak));
    EXPECT_LT(bb.eval(peak + 5.0f), bb.eval(peak));
    EXPECT_EQ(bb.maxValue(), scale);
    for (int l = 360; l <= 830; l += 10) EXPECT_LE(bb.eval(float(l)), bb.maxValue() * (1 + 1e-6f));
}

TEST(Spectra, BlackbodyChromaticity) {
    // CIE standard illuminant A (ISO 11664-2 / CIE 015:2018 eq. 4.1): Planck's law written with
    // T = 2848 K and c2 = 1.435e-2 m K ("2856 K" on the ITS-90 scale), x,y = (0.44757, 0.40745).
    // Our c2 = 1.438776877e-2 m K, so the same curve is at T = 2848 · c2'/c2.
    const float tA = float(2848.0 * 1.438776877 / 1.435);
    const SpectrumPtr a = makeBlackbodySpectrum(tA);
    const dvec3 xyA = chromaticity(integrateXYZ([&](float l) { return a->eval(l); }));
    EXPECT_NEAR(xyA.x, 0.44757, 2e-4);
    EXPECT_NEAR(xyA.y, 0.40745, 2e-4);
    // Hotter is bluer: the blue/red ratio of the RGB-mode value increases with temperature.
    const vec3 c3000 = makeBlackbodySpectrum(3000.0f)->rgbValue(), c9000 = makeBlackbodySpectrum(9000.0f)->rgbValue();
    EXPECT_GT(c9000.b / c9000.r, c3000.b / c3000.r);
    EXPECT_THROW(makeBlackbodySpectrum(0.0f), Error);
    EXPECT_THROW(makeBlackbodySpectrum(-100.0f), Error);
}

TEST(Spectra, PiecewiseLinearEvalAndErrors) {
    const PiecewiseLinearSpectrum s({400, 500, 600}, {1.0f, 3.0f, 2.0f}, SpectrumKind::Unbounded);
    EXPECT_FLOAT_EQ(s.eval(450.0f), 2.0f);
    EXPECT_FLOAT_EQ(s.eval(575.0f), 2.25f);
    EXPECT_FLOAT_EQ(s.eval(500.0f), 3.0f);
    EXPECT_FLOAT_EQ(s.eval(300.0f), 1.0f);  // constant extrapolation
    EXPECT_FLOAT_EQ(s.eval(800.0f), 2.0f);
    EXPECT_FLOAT_EQ(s.maxValue(), 3.0f);
    // Unbounded: RGB mode evaluates at the channel wavelengths.
    const vec3 l = defaultChannelWavelengths();
    EXPECT_EQ(s.rgbValue(), vec3(s.eval(l.x), s.eval(l.y), s.eval(l.z)));
    const SampledSpectrum v = s.sample(SampledWavelengths::rgb(l));
    EXPECT_EQ(v[0], s.eval(l.x));
    EXPECT_EQ(v[2], s.eval(l.z));

    EXPECT_THROW(makePiecewiseLinearSpectrum({}, {}, SpectrumKind::Unbounded), Error);
    EXPECT_THROW(makePiecewiseLinearSpectrum({400, 500}, {1}, SpectrumKind::Unbounded), Error);
    EXPECT_THROW(makePiecewiseLinearSpectrum({500, 400}, {1, 2}, SpectrumKind::Unbounded), Error);
    EXPECT_THROW(makePiecewiseLinearSpectrum({400, 400}, {1, 2}, SpectrumKind::Unbounded), Error);
    EXPECT_THROW(makePiecewiseLinearSpectrum({400, 500}, {1, NAN}, SpectrumKind::Unbounded), Error);
}

TEST(Spectra, TabulatedReflectanceAndIlluminantAreZeroOutsideTheirRange) {
    // Mitsuba's `λ:value` spectra (issue 14, item 8): no data, no energy. Mitsuba 3's
    // bsdf_spheres light is "400:0, 500:8, 600:15.6, 700:18.4": nothing above 700 nm.
    for (SpectrumKind kind : {SpectrumKind::Reflectance, SpectrumKind::Illuminant}) {
        const PiecewiseLinearSpectrum s({400, 500, 700}, {0.5f, 0.8f, 0.7f}, kind);
        EXPECT_EQ(s.eval(399.0f), 0.0f);
        EXPECT_EQ(s.eval(701.0f), 0.0f);
        EXPECT_FLOAT_EQ(s.eval(400.0f), 0.5f);  // the end points are inside
        EXPECT_FLOAT_EQ(s.eval(700.0f), 0.7f);
        EXPECT_FLOAT_EQ(s.maxValue(), 0.8f);
    }
    // Its RGB projection has no light from beyond 700 nm: redder when the end value is extended
    // to 830 nm explicitly (the old constant extrapolation), the same in blue.
    const SpectrumPtr light = makePiecewiseLinearSpectrum({400, 500, 600, 700}, {0, 8, 15.6f, 18.4f}, SpectrumKind::Illuminant);
    const SpectrumPtr extended =
        makePiecewiseLinearSpectrum({360, 400, 500, 600, 700, 830}, {0, 0, 8, 15.6f, 18.4f, 18.4f}, SpectrumKind::Illuminant);
    EXPECT_LT(light->rgbValue().r, 0.999f * extended->rgbValue().r);
    EXPECT_NEAR(light->rgbValue().b, extended->rgbValue().b, 1e-3f * extended->rgbValue().b);
}

TEST(Spectra, SingleValuedSpectrumOfAnEmitterIsD65LikeAFloat) {
    // <spectrum name="radiance" value="0.3"/> is 0.3 x D65 (Y = 1) in Mitsuba 0.6, like <float>
    // (issue 14, item 7): white, not the pink of a flat (equal-energy) spectrum. spectrumFromValue
    // has no scene version and reads it so; Mitsuba 3's flat spectrum for version 2/3 scenes is
    // getSpectrum's (MitsubaRGB.SingleValuedEmissionFollowsTheVersion).
    SpectrumValue v;
    v.constant = 0.3f;
    const SpectrumPtr fromSpectrum = spectrumFromValue(v, SpectrumKind::Illuminant, SourceLocation{});
    const SpectrumPtr fromFloat = spectrumFromNumber(0.3f, SpectrumKind::Illuminant);
    for (float l : {400.0f, 460.0f, 555.0f, 700.0f}) EXPECT_FLOAT_EQ(fromSpectrum->eval(l), fromFloat->eval(l));
    EXPECT_LT(maxAbsDiff(fromSpectrum->rgbValue(), vec3(0.3f)), 1e-3f);
    // A reflectance stays the plain constant.
    const SpectrumPtr refl = spectrumFromValue(v, SpectrumKind::Reflectance, SourceLocation{});
    EXPECT_FLOAT_EQ(refl->eval(420.0f), 0.3f);
    EXPECT_FLOAT_EQ(refl->eval(680.0f), 0.3f);
}

TEST(Spectra, RgbValueOfSpectralReflectanceAndIlluminant) {
    // A perfectly white reflectance reflects D65 with Y = 1: RGB (1, 1, 1).
    const SpectrumPtr white = makePiecewiseLinearSpectrum({360, 830}, {1, 1}, SpectrumKind::Reflectance);
    EXPECT_LT(maxAbsDiff(white->rgbValue(), vec3(1.0f)), 1e-3f);
    // A reflectance tabulated from an RGB-upsampled curve projects back onto that RGB.
    const vec3 rgb(0.6f, 0.25f, 0.1f);
    const SpectrumPtr up = makeRGBSpectrum(rgb, SpectrumKind::Reflectance);
    std::vector<float> ls, vs;
    for (int l = 360; l <= 830; ++l) ls.push_back(float(l)), vs.push_back(up->eval(float(l)));
    const SpectrumPtr tab = makePiecewiseLinearSpectrum(ls, vs, SpectrumKind::Reflectance);
    EXPECT_LT(maxAbsDiff(tab->rgbValue(), rgb), 1e-3f);
    // In RGB mode the spectral reflectance yields its projection.
    const SampledSpectrum v = tab->sample(SampledWavelengths::rgb(defaultChannelWavelengths()));
    for (int i = 0; i < 3; ++i) EXPECT_EQ(v[i], tab->rgbValue()[i]);
    // Illuminant: plain projection; D65 with Y = 1 → (1, 1, 1); equal energy → the IEC matrix row sums.
    EXPECT_LT(maxAbsDiff(makeD65Spectrum()->rgbValue(), vec3(1.0f)), 1e-3f);
    EXPECT_LT(maxAbsDiff(makeD65Spectrum(2.0f)->rgbValue(), vec3(2.0f)), 2e-3f);
    const SpectrumPtr e = makePiecewiseLinearSpectrum({360, 830}, {1, 1}, SpectrumKind::Illuminant);
    const vec3 expectE(xyzToLinearRec709(integrateXYZ([](float) { return 1.0f; })));
    EXPECT_LT(maxAbsDiff(e->rgbValue(), expectE), 1e-5f);
    EXPECT_GT(e->rgbValue().r, e->rgbValue().b);  // illuminant E is redder than D65
}

TEST(Spectra, D65MaxValueBoundsEval) {
    const SpectrumPtr d = makeD65Spectrum(1.5f);
    for (float l = 360; l <= 830; l += 0.5f) ASSERT_LE(d->eval(l), d->maxValue());
    EXPECT_EQ(d->kind(), SpectrumKind::Illuminant);
}

TEST(Spectra, SpdFileParsing) {
    const std::string path = writeFile("ok.spd",
                                       "# a comment\n"
                                       "; another comment\n"
                                       "\n"
                                       "  400   0.5   # trailing comment\n"
                                       "500\t1.5\n"
                                       "0.6 2.5 ; micrometres\n");
    const SpectrumPtr s = loadSpdFile(path, SpectrumKind::Unbounded);
    EXPECT_FLOAT_EQ(s->eval(400.0f), 0.5f);
    EXPECT_FLOAT_EQ(s->eval(450.0f), 1.0f);
    EXPECT_FLOAT_EQ(s->eval(600.0f), 2.5f);  // 0.6 µm = 600 nm
    EXPECT_FLOAT_EQ(s->eval(550.0f), 2.0f);
}

TEST(Spectra, SpdFileErrorsNameFileAndLine) {
    const std::string bad = writeFile("bad.spd", "400 1\n500 x\n");
    EXPECT_NE(errorOf([&] { loadSpdFile(bad, SpectrumKind::Unbounded); }).find(bad + ":2:"), std::string::npos);
    const std::string order = writeFile("order.spd", "# header\n500 1\n400 2\n");
    EXPECT_NE(errorOf([&] { loadSpdFile(order, SpectrumKind::Unbounded); }).find(order + ":3:"), std::string::npos);
    const std::string extra = writeFile("extra.spd", "400 1 2\n");
    EXPECT_NE(errorOf([&] { loadSpdFile(extra, SpectrumKind::Unbounded); }).find(extra + ":1:"), std::string::npos);
    const std::string empty = writeFile("empty.spd", "# nothing\n\n");
    EXPECT_NE(errorOf([&] { loadSpdFile(empty, SpectrumKind::Unbounded); }).find(empty), std::string::npos);
    const std::string missing = (tempDir() / "does_not_exist.spd").string();
    EXPECT_NE(errorOf([&] { loadSpdFile(missing, SpectrumKind::Unbounded); }).find(missing), std::string::npos);
    // Through the scene path: the scene location is prefixed to the file's own message.
    SpectrumValue v;
    v.type = SpectrumValue::Type::File;
    v.path = missing;
    const std::string msg = errorOf([&] { spectrumFromValue(v, SpectrumKind::Unbounded, SourceLocation{"scene.xml", 12}); });
    EXPECT_NE(msg.find("scene.xml:12"), std::string::npos) << msg;
    EXPECT_NE(msg.find(missing), std::string::npos) << msg;
}

TEST(Spectra, MeasuredGoldIor) {
    // Measured Au η (luxpop); the header says Ångström but the values are nm (298.7 … 885.6).
    const std::string path = sourcePath("tests/data/ior/Au.eta.spd");
    const SpectrumPtr s = loadSpdFile(path, SpectrumKind::Unbounded);
    const auto* pl = dynamic_cast<const PiecewiseLinearSpectrum*>(s.get());
    ASSERT_NE(pl, nullptr);
    EXPECT_EQ(pl->lambdas().size(), 56u);
    EXPECT_FLOAT_EQ(pl->lambdas().front(), 298.757050f);
    EXPECT_FLOAT_EQ(pl->lambdas().back(), 885.601257f);
    EXPECT_FLOAT_EQ(s->eval(302.400421f), 1.812f);
    EXPECT_FLOAT_EQ(s->eval(885.601257f), 0.21f);
    // Gold: n well below 1 in the red, above 1 in the blue.
    EXPECT_LT(s->eval(700.0f), 0.3f);
    EXPECT_GT(s->eval(450.0f), 1.0f);
    // Same data as the shared copy when it is available.
    const std::string shared = "/work/shared/data/ior/Au.eta.spd";
    if (fs::exists(shared)) {
        const SpectrumPtr t = loadSpdFile(shared, SpectrumKind::Unbounded);
        for (int l = 360; l <= 830; l += 10) EXPECT_EQ(t->eval(float(l)), s->eval(float(l)));
    }
}

TEST(Spectra, PlanckMatchesPowForm) {
    // planck() forms λ⁵ by multiplication; compare with the textbook c1L / (λ⁵ (e^{c2/λT} − 1)).
    const double c1L = 2.0 * 6.62607015e-34 * sqr(299792458.0), c2 = 6.62607015e-34 * 299792458.0 / 1.380649e-23;
    for (double T : {300.0, 1000.0, 2856.0, 4500.0, 6504.0, 20000.0})
        for (double nm = 360.0; nm <= 830.0; nm += 7.3) {
            const double l = nm * 1e-9;
            const double ref = c1L / (std::pow(l, 5.0) * std::expm1(c2 / (l * T)));
            EXPECT_NEAR(planck(nm, T), ref, 1e-13 * ref);
        }
}

TEST(Spectra, SampledSpectrumPaddedArithmeticMatchesScalarLoop) {
    // SampledSpectrum computes in 4-wide groups over the padded length; every lane below n must
    // equal the plain per-element operation exactly, for every n.
    uint32_t state = 12345u;
    auto next = [&state] {
        state = state * 1664525u + 1013904223u;
        return float(state >> 8) * 0x1p-24f * 4.0f - 1.0f;
    };
    for (int n = 1; n <= kMaxWavelengths; ++n) {
        SampledSpectrum a(n), b(n);
        for (int i = 0; i < n; ++i) {
            a[i] = next();
            b[i] = next();
            if (i % 5 == 3) b[i] = 0.0f;
        }
        const float s = next();
        const SampledSpectrum r[] = {a + b, a - b, a * b, a / b, a + s, a - s, a * s, a / s, s * a, s + a, s - a, -a};
        for (int i = 0; i < n; ++i) {
            const float e[] = {a[i] + b[i], a[i] - b[i], a[i] * b[i], a[i] / b[i], a[i] + s, a[i] - s,
                               a[i] * s,    a[i] / s,    s * a[i],    s + a[i],    s - a[i], -a[i]};
            for (int k = 0; k < 12; ++k) {
                ASSERT_EQ(r[k].size(), n);
                if (std::isnan(e[k])) EXPECT_TRUE(std::isnan(r[k][i]));
                else EXPECT_EQ(r[k][i], e[k]) << "op " << k << " n " << n << " i " << i;
            }
        }
        SampledSpectrum c = a;
        c *= b;
        c += s;
        c -= a;
        c /= 3.0f;
        for (int i = 0; i < n; ++i) EXPECT_EQ(c[i], ((a[i] * b[i] + s) - a[i]) / 3.0f);
        // Queries look at the first n lanes only (padding lanes hold 0/0 etc. here).
        const SampledSpectrum q = a / b;
        EXPECT_EQ(q.hasNonFinite(), [&] {
            for (int i = 0; i < n; ++i)
                if (!std::isfinite(a[i] / b[i])) return true;
            return false;
        }());
        EXPECT_TRUE((a - a).isBlack());
    }
}
