#include "spectral/rgb_upsampling.h"

#include "spectral/cie.h"
#include "spectral/color_space.h"

namespace iris {

float SigmoidPolynomial::maxValue() const {
    float m = std::max((*this)(360.0f), (*this)(830.0f));
    if (c0 != 0.0f) {
        const float tv = -c1 / (2.0f * c0);
        if (tv > 0.0f && tv < 1.0f) m = std::max(m, sigmoid((c0 * tv + c1) * tv + c2));
    }
    return m;
}

vec3 reflectanceRGB(const SigmoidPolynomial& s) {
    return rgbProjection([&](float l) { return s(l); }, SpectrumKind::Reflectance);
}

namespace {

// Double-precision model RGB(c) and its Jacobian dRGB/dc (columns: c0, c1, c2).
struct Model {
    const dvec3* w = reflectanceRGBWeights();
    void eval(const double c[3], dvec3& rgb, double J[3][3]) const {
        rgb = dvec3(0.0);
        for (int r = 0; r < 3; ++r)
            for (int k = 0; k < 3; ++k) J[r][k] = 0.0;
        for (int i = 0; i < kReflectanceWeightCount; ++i) {
            const double t = double(i) / 470.0;  // λ = 360 + i nm
            const double x = (c[0] * t + c[1]) * t + c[2];
            const double q = 1.0 + x * x;
            const double s = 0.5 + x / (2.0 * std::sqrt(q));
            const double ds = 1.0 / (2.0 * q * std::sqrt(q));  // S'(x)
            rgb += s * w[i];
            const double d[3] = {ds * t * t, ds * t, ds};
            for (int r = 0; r < 3; ++r)
                for (int k = 0; k < 3; ++k) J[r][k] += w[i][r] * d[k];
        }
    }
};

// Solve the 3×3 system A x = b (Cramer's rule; A is small and well scaled by the damping).
bool solve3(const double A[3][3], const double b[3], double x[3]) {
    const double det = A[0][0] * (A[1][1] * A[2][2] - A[1][2] * A[2][1]) -
                       A[0][1] * (A[1][0] * A[2][2] - A[1][2] * A[2][0]) +
                       A[0][2] * (A[1][0] * A[2][1] - A[1][1] * A[2][0]);
    if (!std::isfinite(det) || std::abs(det) < 1e-300) return false;
    for (int k = 0; k < 3; ++k) {
        double M[3][3];
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c) M[r][c] = c == k ? b[r] : A[r][c];
        x[k] = (M[0][0] * (M[1][1] * M[2][2] - M[1][2] * M[2][1]) - M[0][1] * (M[1][0] * M[2][2] - M[1][2] * M[2][0]) +
                M[0][2] * (M[1][0] * M[2][1] - M[1][1] * M[2][0])) /
               det;
    }
    return true;
}

double sqNorm(const dvec3& v) { return glm::dot(v, v); }

// Levenberg–Marquardt (Marquardt 1963) minimising |RGB(c) − target|², starting from c.
int levenbergMarquardt(const Model& m, const dvec3& target, double c[3], double tol, int maxIter) {
    dvec3 rgb;
    double J[3][3];
    m.eval(c, rgb, J);
    double err = sqNorm(rgb - target);
    double lambda = 1e-3;
    int it = 0;
    for (; it < maxIter && err > tol * tol; ++it) {
        const dvec3 r = rgb - target;
        double A[3][3], g[3];
        for (int a = 0; a < 3; ++a) {
            g[a] = 0;
            for (int k = 0; k < 3; ++k) g[a] -= J[k][a] * r[k];
            for (int b = 0; b < 3; ++b) {
                A[a][b] = 0;
                for (int k = 0; k < 3; ++k) A[a][b] += J[k][a] * J[k][b];
            }
        }
        bool improved = false;
        for (int attempt = 0; attempt < 30 && !improved; ++attempt) {
            double Ad[3][3];
            for (int a = 0; a < 3; ++a)
                for (int b = 0; b < 3; ++b) Ad[a][b] = A[a][b] + (a == b ? lambda * (A[a][a] + 1e-12) : 0.0);
            double delta[3];
            if (solve3(Ad, g, delta)) {
                double cn[3] = {c[0] + delta[0], c[1] + delta[1], c[2] + delta[2]};
                dvec3 rgbN;
                double JN[3][3];
                m.eval(cn, rgbN, JN);
                const double errN = sqNorm(rgbN - target);
                if (std::isfinite(errN) && errN < err) {
                    for (int k = 0; k < 3; ++k) c[k] = cn[k];
                    rgb = rgbN;
                    for (int a = 0; a < 3; ++a)
                        for (int b = 0; b < 3; ++b) J[a][b] = JN[a][b];
                    err = errN;
                    lambda = std::max(lambda * 0.3, 1e-12);
                    improved = true;
                    break;
                }
            }
            lambda *= 10.0;
        }
        if (!improved) break;  // converged as far as double precision allows
    }
    return it;
}

// Largest component error |RGB(c) − target|.
double residual(const Model& m, const dvec3& target, const double c[3]) {
    dvec3 rgb;
    double J[3][3];
    m.eval(c, rgb, J);
    const dvec3 d = glm::abs(rgb - target);
    return std::max({d.x, d.y, d.z});
}

}  // namespace

SigmoidFit fitSigmoidPolynomial(const vec3& rgbIn) {
    const dvec3 target = glm::clamp(dvec3(rgbIn), 0.0, 1.0);
    const Model model;
    // Start from the grey g of the same mean level: s = const = g, i.e. c = (0, 0, S⁻¹(g)) with
    // S⁻¹(g) = (2g − 1) / (2√(g(1 − g))).
    const double grey = std::clamp((target.x + target.y + target.z) / 3.0, 1e-3, 1.0 - 1e-3);
    const double c2Grey = (2.0 * grey - 1.0) / (2.0 * std::sqrt(grey * (1.0 - grey)));
    double c[3] = {0.0, 0.0, c2Grey};
    // First try the target directly; if that stalls (strongly saturated colours), restart with a
    // continuation in 8 stages from the grey to the target, each warm-starting the next (the paper
    // builds its table the same way, §4), and keep the better of the two.
    int iterations = levenbergMarquardt(model, target, c, 1e-9, 60);
    if (residual(model, target, c) > 1e-6) {
        double cc[3] = {0.0, 0.0, c2Grey};
        const int stages = 8;
        for (int k = 1; k <= stages; ++k) {
            const double a = double(k) / stages;
            const dvec3 t = (1.0 - a) * dvec3(grey) + a * target;
            iterations += levenbergMarquardt(model, t, cc, k == stages ? 1e-9 : 1e-4, k == stages ? 300 : 50);
        }
        if (residual(model, target, cc) < residual(model, target, c))
            for (int k = 0; k < 3; ++k) c[k] = cc[k];
    }
    SigmoidFit fit;
    fit.poly = SigmoidPolynomial{float(c[0]), float(c[1]), float(c[2])};
    const vec3 back = reflectanceRGB(fit.poly);
    const dvec3 d = glm::abs(dvec3(back) - target);
    fit.error = float(std::max({d.x, d.y, d.z}));
    fit.iterations = iterations;
    return fit;
}

}  // namespace iris
