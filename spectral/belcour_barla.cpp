// Belcour & Barla 2017 spectrally integrated Airy reflectance (see belcour_barla.h).
#include "spectral/belcour_barla.h"

#include <algorithm>
#include <cmath>

#include "spectral/color_space.h"

namespace iris {

namespace {

constexpr double kTwoPiD = 6.283185307179586476925286766559;

/// Gaussian fit of the Fourier transform of the CIE 1931 x̄, ȳ, z̄ functions (Belcour & Barla 2017,
/// supplemental material, as listed in the glTF KHR_materials_iridescence specification): with
/// the phase frequency p = 2π·OPD (OPD in metres),
///   S_j(p, shift) = Σ_g a_g sqrt(2π v_g) cos(μ_g p + shift) exp(−v_g p²) / 1.0685e−7,
/// one Gaussian per function plus a second one for x̄'s blue lobe. S(0, 0) ≈ (1, 1, 1).
dvec3 sensitivityXYZ(double opdNm, double shift) {
    const double p = kTwoPiD * opdNm * 1e-9;
    const double a[3] = {5.4856e-13, 4.4201e-13, 5.2481e-13};
    const double mu[3] = {1.6810e+06, 1.7953e+06, 2.2084e+06};
    const double v[3] = {4.3278e+09, 9.3046e+09, 6.6121e+09};
    dvec3 xyz;
    for (int j = 0; j < 3; ++j)
        xyz[j] = a[j] * std::sqrt(kTwoPiD * v[j]) * std::cos(mu[j] * p + shift) * std::exp(-v[j] * p * p);
    xyz.x += 9.7470e-14 * std::sqrt(kTwoPiD * 4.5282e+09) * std::cos(2.2399e+06 * p + shift) *
             std::exp(-4.5282e+09 * p * p);
    return xyz / 1.0685e-7;
}

const dvec3& whiteRGB() {
    static const dvec3 w = xyzToLinearRec709(sensitivityXYZ(0.0, 0.0));
    return w;
}

}  // namespace

dvec3 belcourBarlaSensitivity(double opdNm, double shift) {
    return xyzToLinearRec709(sensitivityXYZ(opdNm, shift)) / whiteRGB();
}

AiryFourier airyFourier(int pol, double cosTheta1, double eta1, double filmEta, double filmThicknessNm,
                        complexd substrate) {
    AiryFourier f;
    cosTheta1 = std::clamp(cosTheta1, 0.0, 1.0);
    const double sin2 = sqr(eta1 / filmEta) * (1.0 - cosTheta1 * cosTheta1);  // Snell, sin²θ2
    if (sin2 >= 1.0) {
        f.totalReflection = true;
        return f;
    }
    const double cos2 = std::sqrt(1.0 - sin2);
    const FresnelAmplitudes top = fresnelAmplitudes(cosTheta1, eta1, complexd(filmEta, 0.0));
    const FresnelAmplitudes bottom = fresnelAmplitudes(cos2, filmEta, substrate);
    const complexd r12 = pol == 0 ? top.rs : top.rp;
    const complexd r23 = pol == 0 ? bottom.rs : bottom.rp;
    const double R12 = std::norm(r12), R23 = std::min(1.0, std::norm(r23));
    f.T121 = 1.0 - R12;
    const double R123 = R12 * R23;
    f.r123 = std::sqrt(R123);
    f.Rs = R123 < 1.0 ? f.T121 * f.T121 * R23 / (1.0 - R123) : 0.0;  // phase-averaged (DC) part
    f.C0 = R12 + f.Rs;
    f.opdNm = 2.0 * filmEta * filmThicknessNm * cos2;  // optical path difference
    // φ = φ21 + φ23: phases of the amplitude reflection inside the film at the top
    // (r21 = −r12) and at the base.
    f.phi = std::arg(-r12) + std::arg(r23);
    return f;
}

double airyFourierAt(const AiryFourier& f, double lambdaNm, int terms) {
    if (f.totalReflection) return 1.0;
    double R = f.C0, Cm = f.Rs - f.T121;
    const double psi = kTwoPiD * f.opdNm / lambdaNm + f.phi;
    for (int m = 1; m <= terms; ++m) {
        Cm *= f.r123;
        R += 2.0 * Cm * std::cos(m * psi);
    }
    return R;
}

double belcourBarlaReflectance(int c, double cosTheta1, double eta1, double filmEta, double filmThicknessNm,
                               complexd substrate) {
    double R = 0.0;
    for (int pol = 0; pol < 2; ++pol) {
        const AiryFourier f = airyFourier(pol, cosTheta1, eta1, filmEta, filmThicknessNm, substrate);
        if (f.totalReflection) {
            R += 0.5;
            continue;
        }
        double I = f.C0, Cm = f.Rs - f.T121;
        const double pOpd = kTwoPiD * f.opdNm * 1e-9;
        for (int m = 1; m <= 32; ++m) {  // harmonics weighted by channel c's sensitivity
            // Stop when the remaining terms are negligible: |Cm| decays as r123^m, and every
            // Gaussian of the fit is below exp(−v_min (m p)²), v_min = 4.3278e9, for all higher m.
            if (std::exp(-4.3278e+09 * sqr(m * pOpd)) < 1e-8) break;
            Cm *= f.r123;
            I += 2.0 * Cm * belcourBarlaSensitivity(m * f.opdNm, m * f.phi)[c];
            if (std::pow(f.r123, m) < 1e-5) break;
        }
        R += 0.5 * I;
    }
    return std::clamp(R, 0.0, 1.0);
}

}  // namespace iris
