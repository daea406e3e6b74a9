#include "core/quadrature.h"

#include <array>
#include <cmath>
#include <memory>
#include <mutex>

#include "core/error.h"

namespace iris {

GaussLegendre::GaussLegendre(int n) : x(n), w(n) {
    for (int i = 0; i < (n + 1) / 2; ++i) {  // the roots come in pairs ±z: compute one of each
        double z = std::cos(M_PI * (i + 0.75) / (n + 0.5)), pp = 0;
        for (int it = 0; it < 100; ++it) {
            double p1 = 1, p2 = 0;  // P_n(z) by the three-term recurrence
            for (int j = 0; j < n; ++j) {
                const double p3 = p2;
                p2 = p1;
                p1 = ((2.0 * j + 1.0) * z * p2 - j * p3) / (j + 1);
            }
            pp = n * (z * p1 - p2) / (z * z - 1.0);  // P_n'(z)
            const double z1 = z;
            z = z1 - p1 / pp;
            if (std::abs(z - z1) < 1e-15) break;
        }
        x[i] = 0.5 * (1.0 - z);
        x[n - 1 - i] = 0.5 * (1.0 + z);
        w[i] = w[n - 1 - i] = 1.0 / ((1.0 - z * z) * pp * pp);
    }
}

const GaussLegendre& gaussLegendre(int n) {
    static std::mutex m;
    static std::array<std::unique_ptr<GaussLegendre>, 257> cache;
    if (n < 1 || n > 256) fail("Gauss-Legendre order must be in [1, 256], got ", n);
    std::lock_guard<std::mutex> lock(m);
    if (!cache[n]) cache[n] = std::make_unique<GaussLegendre>(n);
    return *cache[n];
}

}  // namespace iris
