#include "spectral/mitsuba_rgb.h"

#include <algorithm>
#include <memory>
#include <utility>

#include "spectral/cie.h"
#include "spectral/piecewise_linear_spectrum.h"

namespace iris {

namespace {

// Mitsuba's XYZ → ITU-R BT.709 linear RGB matrix, the same numbers in 0.6 (Spectrum::fromXYZ) and
// 3 (include/mitsuba/core/spectrum.h, xyz_to_srgb); iris's own projections use the 4-digit matrix
// of IEC 61966-2-1 (spectral/color_space.h).
dvec3 mitsubaXyzToLinearRGB(const dvec3& c) {
    return dvec3(3.240479 * c.x - 1.537150 * c.y - 0.498535 * c.z,
                 -0.969256 * c.x + 1.875991 * c.y + 0.041556 * c.z,
                 0.055648 * c.x - 0.204043 * c.y + 1.057311 * c.z);
}

// Mitsuba 3, include/mitsuba/core/spectrum.h: MI_CIE_MIN/MAX, MI_CIE_SAMPLES (the CIE 1931 curves
// and D65 at 5 nm, 360–830 nm), MI_CIE_Y_NORMALIZATION ("a unit-valued spectrum integrates to a
// luminance of 1.0" under the 1000-step rule below) and MI_CIE_D65_NORMALIZATION (cie_d65).
constexpr double kMiCieMin = 360.0, kMiCieMax = 830.0;
constexpr int kMiCieSamples = 95;
constexpr double kMiCieYNormalization = 1.0 / 106.7502593994140625;
constexpr double kMiCieD65Normalization = 1.0 / 98.99741751876255;

// The 5 nm nodes Mitsuba 3 tabulates: the CIE 1931 1 nm table (spectral/cie.h) at every fifth nm,
// and the D65 table, which is at 5 nm already.
struct Mitsuba3Tables {
    dvec3 cmf[kMiCieSamples];
    double d65[kMiCieSamples];
    Mitsuba3Tables() {
        for (int i = 0; i < kMiCieSamples; ++i) {
            const float l = float(kMiCieMin) + 5.0f * float(i);
            cmf[i] = dvec3(cie::xyzBar(l));
            d65[i] = cie::d65(l);
        }
    }
};
const Mitsuba3Tables& mitsuba3Tables() {
    static const Mitsuba3Tables t;
    return t;
}

// Linear interpolant at w of the table, as Mitsuba 3's cie1931_xyz / cie_d65 (w inside the range).
template <typename T>
T lerp5(const T* table, double w) {
    const double t = (w - kMiCieMin) * ((kMiCieSamples - 1) / (kMiCieMax - kMiCieMin));
    const int i0 = std::clamp(int(t), 0, kMiCieSamples - 2);
    const double w1 = t - double(i0);
    return (1.0 - w1) * table[i0] + w1 * table[i0 + 1];
}

}  // namespace

vec3 mitsuba3SpectrumToRGB(const std::vector<float>& lambdas, const std::vector<float>& values, bool d65, bool bounded) {
    // Mitsuba 3, src/core/spectrum.cpp, spectrum_list_to_srgb (the values scaled by
    // MI_CIE_Y_NORMALIZATION as its callers do, include/mitsuba/render/ior.h, src/core/xml.cpp).
    const Mitsuba3Tables& tab = mitsuba3Tables();
    dvec3 xyz(0.0);
    if (lambdas.size() >= 2) {
        constexpr int kSteps = 1000;
        for (int i = 0; i < kSteps; ++i) {
            const double w = kMiCieMin + (i / double(kSteps - 1)) * (kMiCieMax - kMiCieMin);
            if (w < lambdas.front() || w > lambdas.back()) continue;
            // The interval [w0, w1] holding w (its last interval at the last sample).
            const size_t idx = std::min(size_t(std::upper_bound(lambdas.begin(), lambdas.end(), float(w)) - lambdas.begin()),
                                        lambdas.size() - 1) - 1;
            const double w0 = lambdas[idx], w1 = lambdas[idx + 1], v0 = values[idx], v1 = values[idx + 1];
            const double v = ((w - w1) * v0 + (w0 - w) * v1) / (w0 - w1);
            xyz += lerp5(tab.cmf, w) * v * (d65 ? lerp5(tab.d65, w) * kMiCieD65Normalization : 1.0);
        }
        xyz *= (kMiCieMax - kMiCieMin) / double(kSteps) * kMiCieYNormalization;
    }
    dvec3 rgb = mitsubaXyzToLinearRGB(xyz);
    // "bounded": clipped to [0, 1]; otherwise only negative values are clamped.
    rgb = bounded ? glm::clamp(rgb, 0.0, 1.0) : glm::max(rgb, 0.0);
    return vec3(rgb);
}

vec3 mitsuba06SpectrumToRGB(const std::vector<float>& lambdas, const std::vector<float>& values) {
    // Mitsuba 0.6, src/libcore/spectrum.cpp: X = ProductSpectrum(S, x̄).average(360, 830) /
    // ȳ.average(360, 830), ... with S and the 1 nm CIE curves piecewise linear (InterpolatedSpectrum,
    // 0 outside the table). On every piece between the merged breakpoints both factors are linear,
    // so Simpson's rule integrates their product exactly (0.6 integrates it adaptively).
    const int first = cie::kQuadratureFirst, last = cie::kQuadratureLast;
    std::vector<double> breaks;
    for (int l = first; l <= last; ++l) breaks.push_back(l);
    for (float l : lambdas)
        if (l > first && l < last) breaks.push_back(l);
    std::sort(breaks.begin(), breaks.end());
    breaks.erase(std::unique(breaks.begin(), breaks.end()), breaks.end());
    dvec3 xyz(0.0);
    for (size_t b = 0; b + 1 < breaks.size(); ++b) {
        const double a = breaks[b], e = breaks[b + 1], m = 0.5 * (a + e);
        if (lambdas.size() < 2 || m < lambdas.front() || m > lambdas.back()) continue;  // S = 0 here
        const size_t j = std::min(size_t(std::upper_bound(lambdas.begin(), lambdas.end(), float(m)) - lambdas.begin()),
                                  lambdas.size() - 1) - 1;
        const double la = lambdas[j], lb = lambdas[j + 1];
        const auto s = [&](double l) { return values[j] + (values[j + 1] - values[j]) * (l - la) / (lb - la); };
        const int n = int(m);  // the 1 nm CIE interval [n, n + 1] holding the piece
        const dvec3 ca(cie::xyzBar(float(n))), cb(cie::xyzBar(float(n + 1)));
        const auto cmf = [&](double l) { return ca + (cb - ca) * (l - n); };
        xyz += (e - a) / 6.0 * (s(a) * cmf(a) + 4.0 * s(m) * cmf(m) + s(e) * cmf(e));
    }
    double yIntegral = 0;  // ∫ ȳ: trapezoids of the 1 nm table (InterpolatedSpectrum::average)
    for (int l = first; l < last; ++l) yIntegral += 0.5 * (double(cie::yBar(float(l))) + cie::yBar(float(l + 1)));
    return vec3(mitsubaXyzToLinearRGB(xyz / yIntegral));
}

void mitsuba06ZeroExtend(std::vector<float>& lambdas, std::vector<float>& values) {
    // Mitsuba 0.6, src/libcore/spectrum.cpp, InterpolatedSpectrum::zeroExtend.
    if (lambdas.size() < 2) return;
    const float spacing = (lambdas.back() - lambdas.front()) / float(lambdas.size() - 1);
    if (values.front() != 0.0f) {
        lambdas.insert(lambdas.begin(), lambdas.front() - spacing);
        values.insert(values.begin(), 0.0f);
    }
    if (values.back() != 0.0f) {
        lambdas.push_back(lambdas.back() + spacing);
        values.push_back(0.0f);
    }
}

vec3 mitsubaRGBModeValue(const std::vector<float>& lambdas, const std::vector<float>& values, SpectrumKind kind,
                         MitsubaTableSource source, MitsubaConvention convention) {
    const bool preset = source == MitsubaTableSource::ConductorPreset;
    if (convention == MitsubaConvention::Mitsuba06) {
        if (preset) return mitsuba06SpectrumToRGB(lambdas, values);
        std::vector<float> l = lambdas, v = values;
        mitsuba06ZeroExtend(l, v);
        return glm::max(mitsuba06SpectrumToRGB(l, v), vec3(0.0f));  // Spectrum::clampNegative
    }
    if (preset) return mitsuba3SpectrumToRGB(lambdas, values, false, false);
    // Properties::get_texture_impl: bounded = !(emitter || unbounded), d65 = !emitter.
    const bool emitter = kind == SpectrumKind::Illuminant;
    return mitsuba3SpectrumToRGB(lambdas, values, !emitter, kind == SpectrumKind::Reflectance);
}

namespace {

/// Spectral mode: the wrapped spectrum (a table, or a constant); RGB mode: the triple, for every kind.
class MitsubaTableSpectrum final : public Spectrum {
public:
    MitsubaTableSpectrum(SpectrumPtr table, const vec3& rgb)
        : Spectrum(table->kind()), table_(std::move(table)), rgb_(rgb),
          max_(std::max(table_->maxValue(), std::max(rgb.x, std::max(rgb.y, rgb.z)))) {}
    float eval(float lambda) const override { return table_->eval(lambda); }
    float maxValue() const override { return max_; }
    SampledSpectrum sample(const SampledWavelengths& wl) const override {
        if (!wl.isRGB()) return table_->sample(wl);
        SampledSpectrum s(wl.size());
        for (int i = 0; i < 3; ++i) s[i] = rgb_[i];
        return s;
    }
    vec3 rgbValue() const override { return rgb_; }

private:
    SpectrumPtr table_;
    vec3 rgb_;
    float max_;
};

}  // namespace

SpectrumPtr mitsuba3UniformEmission(float v) {
    const vec3 rgb = vec3(double(v) * mitsubaXyzToLinearRGB(dvec3(1.0)));
    return std::make_shared<MitsubaTableSpectrum>(std::make_shared<ConstantSpectrum>(v, SpectrumKind::Illuminant), rgb);
}

SpectrumPtr withMitsubaRGBModeValue(SpectrumPtr table, MitsubaTableSource source, MitsubaConvention convention) {
    const auto* pl = dynamic_cast<const PiecewiseLinearSpectrum*>(table.get());
    if (!pl) return table;
    const vec3 rgb = mitsubaRGBModeValue(pl->lambdas(), pl->values(), pl->kind(), source, convention);
    return std::make_shared<MitsubaTableSpectrum>(std::move(table), rgb);
}

}  // namespace iris
