// Gauss–Legendre quadrature on [0, 1]: ∫₀¹ f ≈ Σᵢ wᵢ f(xᵢ), exact for polynomials of degree
// ≤ 2n − 1. Nodes are the roots of the Legendre polynomial P_n found by Newton iteration from
// cos(π(i + 3/4)/(n + 1/2)), weights 2/((1 − z²) P_n'(z)²) on [−1, 1] (Press et al., Numerical
// Recipes 3rd ed. §4.6.1), mapped to [0, 1] (x = (1 ∓ z)/2, weights halved). Used by the film
// coating's hemispherical reflectance and the rough-plastic tables.
#pragma once

#include <vector>

namespace iris {

struct GaussLegendre {
    std::vector<double> x, w;  // ascending nodes in (0, 1) and their weights (Σ w = 1)
    explicit GaussLegendre(int n);
};

/// The n-point rule, computed once per n (thread-safe); n in [1, 256], else iris::Error.
const GaussLegendre& gaussLegendre(int n);

}  // namespace iris
