#include "spectral/blackbody_spectrum.h"

#include "core/error.h"
#include "spectral/color_space.h"

namespace iris {

namespace {
// CODATA 2018 exact SI constants (h, c, k_B); c1L = 2hc² (radiance form of the first radiation
// constant) and c2 = hc/k_B = 1.438776877e-2 m·K, as used with Planck's law in CIE 015:2018 §5.
constexpr double kH = 6.62607015e-34;   // J·s
constexpr double kC = 299792458.0;      // m/s
constexpr double kKB = 1.380649e-23;    // J/K
constexpr double kC1L = 2.0 * kH * kC * kC;
constexpr double kC2 = kH * kC / kKB;
// Wien's displacement: λ_max·T = c2 / x with x the root of x = 5(1 − e^{−x}), x = 4.965114231744276.
constexpr double kWienX = 4.965114231744276;
}  // namespace

double planck(double lambdaNm, double T) {
    if (lambdaNm <= 0.0 || T <= 0.0) return 0.0;
    const double l = lambdaNm * 1e-9;  // m
    // Planck's law: B(λ, T) = c1L / (λ⁵ (exp(c2 / (λT)) − 1)).
    const double l2 = l * l;  // λ⁵ by multiplication (pow(l, 5.0) costs a general pow)
    return kC1L / (l2 * l2 * l * std::expm1(kC2 / (l * T)));
}

BlackbodySpectrum::BlackbodySpectrum(float temperatureK, float scale)
    : Spectrum(SpectrumKind::Illuminant), T_(temperatureK), scale_(scale) {
    if (!std::isfinite(temperatureK) || temperatureK <= 0.0f)
        fail("blackbody temperature must be a positive number of kelvins, got ", temperatureK);
    if (!std::isfinite(scale)) fail("blackbody scale must be finite, got ", scale);
    const double peakNm = kC2 / (kWienX * double(T_)) * 1e9;
    invPeak_ = 1.0 / planck(peakNm, T_);
    rgb_ = rgbProjection([this](float l) { return eval(l); }, SpectrumKind::Illuminant);
}

float BlackbodySpectrum::eval(float lambda) const { return float(scale_ * planck(lambda, T_) * invPeak_); }

}  // namespace iris
