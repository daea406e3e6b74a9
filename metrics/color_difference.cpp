// CIELAB conversion and CIEDE2000. Equation numbers refer to G. Sharma, W. Wu, E. N. Dalal, "The
// CIEDE2000 color-difference formula: implementation notes, supplementary test data, and
// mathematical observations", Color Research & Application 30(1):21–30, 2005.
#include "metrics/color_difference.h"

#include <algorithm>
#include <cmath>

namespace iris {

namespace {

constexpr double kPiD = 3.14159265358979323846;
double deg2rad(double d) { return d * (kPiD / 180.0); }
double rad2deg(double r) { return r * (180.0 / kPiD); }

// Linear Rec.709 → XYZ (D65), IEC 61966-2-1:1999 (sRGB) matrix, 7-digit form.
constexpr double kM[3][3] = {{0.4124564, 0.3575761, 0.1804375},
                             {0.2126729, 0.7151522, 0.0721750},
                             {0.0193339, 0.1191920, 0.9503041}};
// Reference white: XYZ of RGB (1,1,1), i.e. the row sums (D65 with Y = 1).
constexpr double kWhite[3] = {kM[0][0] + kM[0][1] + kM[0][2], kM[1][0] + kM[1][1] + kM[1][2],
                              kM[2][0] + kM[2][1] + kM[2][2]};

// Inverse of kM by the adjugate (cofactors over the determinant), once.
struct InverseMatrix {
    double m[3][3];
    InverseMatrix() {
        auto cof = [](int r, int c) {
            const int r0 = (r + 1) % 3, r1 = (r + 2) % 3, c0 = (c + 1) % 3, c1 = (c + 2) % 3;
            return kM[r0][c0] * kM[r1][c1] - kM[r0][c1] * kM[r1][c0];
        };
        const double det = kM[0][0] * cof(0, 0) + kM[0][1] * cof(0, 1) + kM[0][2] * cof(0, 2);
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c) m[r][c] = cof(c, r) / det;  // (adj M)_rc = cofactor_cr
    }
};
const InverseMatrix kMInverse;

// CIELAB f(t) (CIE 15:2004, eq. 8.3–8.4): cube root above (6/29)^3, linear below.
double labF(double t) {
    constexpr double d = 6.0 / 29.0;
    return t > d * d * d ? std::cbrt(t) : t / (3.0 * d * d) + 4.0 / 29.0;
}

// Hue angle in degrees in [0, 360), 0 for a'=b=0 (Sharma eq. 4).
double hueDeg(double b, double ap) {
    if (ap == 0.0 && b == 0.0) return 0.0;
    double h = rad2deg(std::atan2(b, ap));
    return h < 0.0 ? h + 360.0 : h;
}

}  // namespace

void linearRec709ToXYZ(double r, double g, double b, double xyz[3]) {
    for (int i = 0; i < 3; ++i) xyz[i] = kM[i][0] * r + kM[i][1] * g + kM[i][2] * b;
}

void xyzToLinearRec709(const double xyz[3], double rgb[3]) {
    for (int i = 0; i < 3; ++i)
        rgb[i] = kMInverse.m[i][0] * xyz[0] + kMInverse.m[i][1] * xyz[1] + kMInverse.m[i][2] * xyz[2];
}

void rec709WhiteXYZ(double xyz[3]) {
    for (int i = 0; i < 3; ++i) xyz[i] = kWhite[i];
}

Lab linearRec709ToLab(double r, double g, double b) {
    double xyz[3];
    linearRec709ToXYZ(r, g, b, xyz);
    const double fx = labF(xyz[0] / kWhite[0]), fy = labF(xyz[1] / kWhite[1]), fz = labF(xyz[2] / kWhite[2]);
    // CIE 15:2004 eq. 8.2: L* = 116 f(Y/Yn) − 16, a* = 500 (f(X/Xn) − f(Y/Yn)), b* = 200 (f(Y/Yn) − f(Z/Zn)).
    return Lab{116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)};
}

double ciede2000(const Lab& x, const Lab& y) {
    const double pow25_7 = 6103515625.0;  // 25^7
    // Eq. 2–3: chroma-dependent a* rescaling G.
    const double c1 = std::hypot(x.a, x.b), c2 = std::hypot(y.a, y.b);
    const double cBar = 0.5 * (c1 + c2);
    const double cBar7 = std::pow(cBar, 7.0);
    const double G = 0.5 * (1.0 - std::sqrt(cBar7 / (cBar7 + pow25_7)));
    // Eq. 4–5: a', C', h'.
    const double a1p = (1.0 + G) * x.a, a2p = (1.0 + G) * y.a;
    const double c1p = std::hypot(a1p, x.b), c2p = std::hypot(a2p, y.b);
    const double h1p = hueDeg(x.b, a1p), h2p = hueDeg(y.b, a2p);
    // Eq. 8–11: ΔL', ΔC', Δh', ΔH'.
    const double dLp = y.L - x.L;
    const double dCp = c2p - c1p;
    const double cProd = c1p * c2p;
    double dhp = 0.0;
    if (cProd != 0.0) {
        dhp = h2p - h1p;
        if (dhp > 180.0) dhp -= 360.0;
        else if (dhp < -180.0) dhp += 360.0;
    }
    const double dHp = 2.0 * std::sqrt(cProd) * std::sin(deg2rad(dhp / 2.0));
    // Eq. 12–14: means L̄', C̄', h̄'.
    const double lBarP = 0.5 * (x.L + y.L);
    const double cBarP = 0.5 * (c1p + c2p);
    double hBarP = h1p + h2p;
    if (cProd != 0.0) {
        if (std::abs(h1p - h2p) <= 180.0) hBarP = 0.5 * (h1p + h2p);
        else if (h1p + h2p < 360.0) hBarP = 0.5 * (h1p + h2p + 360.0);
        else hBarP = 0.5 * (h1p + h2p - 360.0);
    }
    // Eq. 15–21: weighting functions and rotation term.
    const double T = 1.0 - 0.17 * std::cos(deg2rad(hBarP - 30.0)) + 0.24 * std::cos(deg2rad(2.0 * hBarP)) +
                     0.32 * std::cos(deg2rad(3.0 * hBarP + 6.0)) - 0.20 * std::cos(deg2rad(4.0 * hBarP - 63.0));
    const double dTheta = 30.0 * std::exp(-((hBarP - 275.0) / 25.0) * ((hBarP - 275.0) / 25.0));
    const double cBarP7 = std::pow(cBarP, 7.0);
    const double RC = 2.0 * std::sqrt(cBarP7 / (cBarP7 + pow25_7));
    const double l50 = (lBarP - 50.0) * (lBarP - 50.0);
    const double SL = 1.0 + 0.015 * l50 / std::sqrt(20.0 + l50);
    const double SC = 1.0 + 0.045 * cBarP;
    const double SH = 1.0 + 0.015 * cBarP * T;
    const double RT = -std::sin(deg2rad(2.0 * dTheta)) * RC;
    // Eq. 22 with kL = kC = kH = 1.
    const double tl = dLp / SL, tc = dCp / SC, th = dHp / SH;
    return std::sqrt(std::max(0.0, tl * tl + tc * tc + th * th + RT * tc * th));
}

}  // namespace iris
