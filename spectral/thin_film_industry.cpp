#include "spectral/thin_film_industry.h"

#include <algorithm>
#include <cmath>

namespace iris {

namespace {
constexpr double kPiD = 3.14159265358979323846;
}  // namespace

double schlickFresnel(double f0, double cosTheta) {
    const double m = std::clamp(1.0 - cosTheta, 0.0, 1.0);
    const double m2 = m * m;
    return f0 + (1.0 - f0) * m2 * m2 * m;  // Schlick 1994; glTF 2.0 Appendix B.3.4
}

double iorToFresnel0(double transmittedIor, double incidentIor) {
    const double r = (transmittedIor - incidentIor) / (transmittedIor + incidentIor);
    return r * r;  // KHR_materials_iridescence, IorToFresnel0
}

double fresnel0ToIor(double f0) {
    const double s = std::sqrt(std::max(f0, 0.0));
    return (1.0 + s) / (1.0 - s);  // KHR_materials_iridescence, Fresnel0ToIor
}

dvec3 khrSensitivity(double opdNm, const dvec3& shift) {
    // KHR_materials_iridescence, "Analytic Spectral Integration", evalSensitivity: Gaussian fits
    // (val, pos, var) of the CIE 1931 functions' Fourier transform, x̄ with a second lobe.
    const double phase = 2.0 * kPiD * opdNm * 1.0e-9;
    const dvec3 val(5.4856e-13, 4.4201e-13, 5.2481e-13);
    const dvec3 pos(1.6810e+06, 1.7953e+06, 2.2084e+06);
    const dvec3 var(4.3278e+09, 9.3046e+09, 6.6121e+09);
    dvec3 xyz;
    for (int c = 0; c < 3; ++c)
        xyz[c] = val[c] * std::sqrt(2.0 * kPiD * var[c]) * std::cos(pos[c] * phase + shift[c]) * std::exp(-phase * phase * var[c]);
    xyz.x += 9.7470e-14 * std::sqrt(2.0 * kPiD * 4.5282e+09) * std::cos(2.2399e+06 * phase + shift[0]) *
             std::exp(-4.5282e+09 * phase * phase);
    xyz /= 1.0685e-7;
    // XYZ_TO_REC709 as the README prints it (column-major GLSL mat3, so these are its rows).
    return dvec3(3.2404542 * xyz.x - 1.5371385 * xyz.y - 0.4985314 * xyz.z,
                 -0.9692660 * xyz.x + 1.8760108 * xyz.y + 0.0415560 * xyz.z,
                 0.0556434 * xyz.x - 0.2040259 * xyz.y + 1.0572252 * xyz.z);
}

dvec3 khrIridescentFresnel(double outsideIor, double filmIor, const dvec3& baseF0, double thicknessNm, double cosTheta1) {
    // Snell into the film; total internal reflection gives 1 ("Material Interfaces").
    const double sin2 = (outsideIor / filmIor) * (outsideIor / filmIor) * (1.0 - cosTheta1 * cosTheta1);
    const double cos2sq = 1.0 - sin2;
    if (cos2sq < 0.0) return dvec3(1.0);
    const double cosTheta2 = std::sqrt(cos2sq);
    // First interface: Schlick from the film's F0 against the outside.
    const double R12 = schlickFresnel(iorToFresnel0(filmIor, outsideIor), cosTheta1);
    const double T121 = 1.0 - R12;
    // "Phase Shift": 0 when the hit medium is denser, else π; polarisation ignored.
    const double phi12 = filmIor < outsideIor ? kPiD : 0.0;
    const double phi21 = kPiD - phi12;
    dvec3 I;
    const double OPD = 2.0 * filmIor * thicknessNm * cosTheta2;
    for (int c = 0; c < 3; ++c) {
        // Second interface: the base index from F0, Schlick at θ2. The README adds 1e−4 to F0 as a
        // guard; that divides by zero from F0 = 0.9999 on, so the sum is also capped at 0.9999.
        const double baseIor = fresnel0ToIor(std::min(baseF0[c] + 0.0001, 0.9999));
        const double R23 = schlickFresnel(iorToFresnel0(baseIor, filmIor), cosTheta2);
        const double phi23 = baseIor < filmIor ? kPiD : 0.0;
        const double phi = phi21 + phi23;
        // "Analytic Spectral Integration": C0 plus harmonics m = 1, 2 weighted by S(m·OPD, m·φ).
        const double R123 = std::clamp(R12 * R23, 1e-5, 0.9999);
        const double r123 = std::sqrt(R123);
        const double Rs = T121 * T121 * R23 / (1.0 - R123);
        double value = R12 + Rs;
        double Cm = Rs - T121;
        for (int m = 1; m <= 2; ++m) {
            Cm *= r123;
            const dvec3 S = 2.0 * khrSensitivity(m * OPD, dvec3(m * phi));
            value += Cm * S[c];
        }
        I[c] = std::max(value, 0.0);
    }
    return I;
}

complexd gulbrandsenIor(double r, double g) {
    r = std::clamp(r, 0.0, 0.99);
    g = std::clamp(g, 0.0, 1.0);
    const double sr = std::sqrt(r);
    const double nMin = (1.0 - r) / (1.0 + r), nMax = (1.0 + sr) / (1.0 - sr);  // Gulbrandsen 2014 §3
    const double n = g * nMin + (1.0 - g) * nMax;
    const double k2 = (r * (n + 1.0) * (n + 1.0) - (n - 1.0) * (n - 1.0)) / (1.0 - r);
    return {n, std::sqrt(std::max(k2, 0.0))};
}

double exactThinFilmReflectance(double lambdaNm, double cosTheta1, double outsideIor, double filmIor, double thicknessNm,
                                complexd substrate) {
    const Layer film{complexd(filmIor, 0.0), std::max(thicknessNm, 0.0)};
    return airySingleFilm(lambdaNm, std::clamp(cosTheta1, 0.0, 1.0), outsideIor, film, substrate).R();
}

}  // namespace iris
