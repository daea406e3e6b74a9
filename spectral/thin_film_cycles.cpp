// Blender Cycles 4.2's thin film (see thin_film_cycles.h for the sources: commit 17f2cdd1,
// intern/cycles/kernel/closure/bsdf_util.h and intern/cycles/scene/shader.cpp).
#include "spectral/thin_film_cycles.h"

#include <algorithm>
#include <cmath>

namespace iris {

namespace {
constexpr double kPiD = 3.14159265358979323846;
}  // namespace

double cyclesSmoothstep(double e0, double e1, double x) {
    if (x < e0) return 0.0;
    if (x >= e1) return 1.0;
    const double t = (x - e0) / (e1 - e0);
    return (3.0 - 2.0 * t) * t * t;  // Cycles util/math smoothstep
}

double cyclesFilmIndex(double outsideIor, double filmIor, double thicknessNm) {
    // fresnel_iridescence: "For films below 30nm, the wave-optic-based Airy summation approach no
    // longer applies, so blend towards the case without coating."
    if (thicknessNm >= 30.0) return filmIor;
    const double t = cyclesSmoothstep(0.0, 30.0, thicknessNm);
    return outsideIor + (filmIor - outsideIor) * t;
}

CyclesPolarizedFresnel cyclesFresnelDielectricPolarized(double cosThetaI, double eta) {
    CyclesPolarizedFresnel f;
    // fresnel_dielectric_polarized: η² cos²θt = η² − sin²θi; ≤ 0 is total internal reflection.
    const double etaCosTSq = eta * eta - (1.0 - cosThetaI * cosThetaI);
    if (etaCosTSq <= 0.0) return f;
    const double ci = std::abs(cosThetaI);
    const double ct = std::sqrt(etaCosTSq) / eta;  // |cosθt|
    const double rs = (ci - eta * ct) / (ci + eta * ct);
    const double rp = (eta * ci - ct) / (eta * ci + ct);
    f.Rs = rs * rs;
    f.Rp = rp * rp;
    f.phiS = rs < 0.0 ? kPiD : 0.0;  // phase shift on reflection: 0 or π by the amplitude's sign
    f.phiP = rp < 0.0 ? kPiD : 0.0;
    f.cosT = ct;
    f.tir = false;
    return f;
}

dvec3 cyclesSensitivityXYZ(double opdNm, double shift) {
    // iridescence_lookup_sensitivity: Belcour & Barla's Gaussian fit (val, pos, var) of the CIE 1931
    // functions' Fourier transform, with a second Gaussian for x̄ (its blue lobe).
    const double phase = 2.0 * kPiD * opdNm * 1e-9;
    const dvec3 val(5.4856e-13, 4.4201e-13, 5.2481e-13);
    const dvec3 pos(1.6810e+06, 1.7953e+06, 2.2084e+06);
    const dvec3 var(4.3278e+09, 9.3046e+09, 6.6121e+09);
    dvec3 xyz;
    for (int c = 0; c < 3; ++c)
        xyz[c] = val[c] * std::sqrt(2.0 * kPiD * var[c]) * std::cos(pos[c] * phase + shift) * std::exp(-phase * phase * var[c]);
    xyz.x += 1.64408e-8 * std::cos(2.2399e+06 * phase + shift) * std::exp(-4.5282e+09 * phase * phase);
    return xyz / 1.0685e-7;
}

dvec3 cyclesAirySummationXYZ(double T121, double R12, double R23, double opdNm, double phi) {
    if (R23 == 1.0) return dvec3(1.0);  // total internal reflection at the base
    const double R123 = R12 * R23;
    const double r123 = std::sqrt(R123);
    const double Rs = T121 * T121 * R23 / (1.0 - R123);
    dvec3 R(R12 + Rs);  // C0, the same in X, Y and Z
    double Cm = Rs - T121;
    for (int m = 1; m <= 3; ++m) {  // "Truncate after m=3"
        Cm *= r123;
        R += Cm * 2.0 * cyclesSensitivityXYZ(m * opdNm, m * phi);
    }
    return R;
}

dvec3 cyclesFresnelIridescenceXYZ(double eta1, double eta2, double eta3, double cosTheta1, double thicknessNm) {
    const CyclesPolarizedFresnel top = cyclesFresnelDielectricPolarized(cosTheta1, eta2 / eta1);
    if (top.Rs == 1.0 && top.Rp == 1.0) return dvec3(1.0);  // total reflection at the top
    const double opd = 2.0 * eta2 * thicknessNm * top.cosT;
    const CyclesPolarizedFresnel bottom = cyclesFresnelDielectricPolarized(top.cosT, eta3 / eta2);
    if (bottom.Rs == 1.0 && bottom.Rp == 1.0) return dvec3(1.0);
    // φ = π − φ12 + φ23: the internal reflection 2→1 has the opposite sign of r12.
    const dvec3 s = cyclesAirySummationXYZ(1.0 - top.Rs, top.Rs, bottom.Rs, opd, kPiD - top.phiS + bottom.phiS);
    const dvec3 p = cyclesAirySummationXYZ(1.0 - top.Rp, top.Rp, bottom.Rp, opd, kPiD - top.phiP + bottom.phiP);
    return 0.5 * (s + p);
}

dvec3 cyclesXyzToRec709(const dvec3& xyz) {
    // shader.cpp, init_xyz_transforms: xyz_to_rec709 (rows).
    return dvec3(3.2404542 * xyz.x - 1.5371385 * xyz.y - 0.4985314 * xyz.z,
                 -0.9692660 * xyz.x + 1.8760108 * xyz.y + 0.0415560 * xyz.z,
                 0.0556434 * xyz.x - 0.2040259 * xyz.y + 1.0572252 * xyz.z);
}

const dvec3& cyclesRec709WhiteXYZ() {
    // white_xyz = rgb_to_xyz · (1, 1, 1), rgb_to_xyz the inverse of xyz_to_rgb.
    static const dvec3 white = [] {
        const glm::dmat3 m(cyclesXyzToRec709(dvec3(1, 0, 0)), cyclesXyzToRec709(dvec3(0, 1, 0)), cyclesXyzToRec709(dvec3(0, 0, 1)));
        return glm::inverse(m) * dvec3(1.0);
    }();
    return white;
}

dvec3 cyclesThinFilmRGB(double outsideIor, double filmIor, double baseIor, double cosTheta1, double thicknessNm) {
    cosTheta1 = std::clamp(std::abs(cosTheta1), 0.0, 1.0);
    if (thicknessNm <= kCyclesThinFilmCutoffNm) {  // no film: fresnel_dielectric, unpolarised
        const CyclesPolarizedFresnel f = cyclesFresnelDielectricPolarized(cosTheta1, baseIor / outsideIor);
        return dvec3(0.5 * (f.Rs + f.Rp));
    }
    const double eta2 = cyclesFilmIndex(outsideIor, filmIor, thicknessNm);
    const dvec3 xyz = cyclesFresnelIridescenceXYZ(outsideIor, eta2, baseIor, cosTheta1, thicknessNm);
    // "we just multiply by the white point here" (E → the working space's white), then XYZ → RGB.
    const dvec3 rgb = cyclesXyzToRec709(xyz * cyclesRec709WhiteXYZ());
    return glm::clamp(rgb, dvec3(0.0), dvec3(1.0));
}

}  // namespace iris
