// RGB → spectrum upsampling of Jakob & Hanika 2019, "A Low-Dimensional Function Space for
// Efficient Spectral Upsampling" (Computer Graphics Forum 38(2), Eurographics): a reflectance is
//   s(λ) = S(c0 t² + c1 t + c2),   S(x) = ½ + x / (2√(1 + x²))      (paper eqs. 3 and 4),
// here with the normalised wavelength t = (λ − 360 nm) / 470 nm for conditioning. The three
// coefficients are fitted per colour (no precomputed table) so that the D65-lit reflectance
// projects back onto the requested linear Rec.709 RGB (spectral/color_space.h).
#pragma once

#include "core/math.h"

namespace iris {

struct SigmoidPolynomial {
    float c0 = 0, c1 = 0, c2 = 0;  // coefficients in t = (λ − 360) / 470

    /// S(x) (paper eq. 4). x is clamped to ±2^63 first: from |x| = 2^64 on, x² overflows and the
    /// formula gave ½ instead of 1 or 0 (by sign). At ±2^63 it gives exactly 1 or 0 (x² = 2^126 and
    /// its square root are exact), which is S(x) rounded to float for x ≥ 2^63 and what the float
    /// formula gives (cancellation) for x ≤ −2^63. Infinities give 1 / 0, NaN stays NaN, and for
    /// |x| < 2^63 nothing changes. Branch-free, so lane loops over wavelengths vectorise.
    [[gnu::always_inline]] static float sigmoid(float x) {
        constexpr float kBig = 9.223372036854775808e18f;  // 2^63
        x = std::clamp(x, -kBig, kBig);
        return 0.5f + x / (2.0f * std::sqrt(1.0f + x * x));
    }
    [[gnu::always_inline]] static float normalisedWavelength(float lambda) { return (lambda - 360.0f) * (1.0f / 470.0f); }
    [[gnu::always_inline]] float operator()(float lambda) const {
        const float t = normalisedWavelength(lambda);
        return sigmoid((c0 * t + c1) * t + c2);
    }
    /// Maximum over [360, 830] nm (S is monotonic, so at an end point or the parabola's vertex).
    float maxValue() const;
};

struct SigmoidFit {
    SigmoidPolynomial poly;
    float error = 0;   // max |RGB(s) − target| component error after the fit
    int iterations = 0;
};

/// Fit s so that the reflectance under D65 reproduces `rgb` (components clamped to [0, 1]).
/// Levenberg–Marquardt on the RGB residual with a continuation from mid-grey (as the paper's
/// table construction, §4, starts from grey), double precision. Greys are fitted too (c0 = c1 = 0),
/// but exact 0 / 1 cannot be reached by S and should be represented by constant spectra.
SigmoidFit fitSigmoidPolynomial(const vec3& rgb);

/// Linear Rec.709 RGB of a sigmoid reflectance under D65 (the projection the fit inverts).
vec3 reflectanceRGB(const SigmoidPolynomial& s);

}  // namespace iris
