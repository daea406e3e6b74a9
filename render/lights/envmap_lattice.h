// Where the texels of a latitude-longitude environment map sit in (u, v) = (φ/2π, θ/π), and the
// bilinear interpolation between them. Mitsuba 0.6 and Mitsuba 3 place them differently:
//  - Mitsuba 0.6 (src/emitters/envmap.cpp → MIPMap::evalBilinear): texel (x, y) at the centre of
//    its cell, u = (x + ½)/W, v = (y + ½)/H; periodic in u, rows clamped at the poles.
//  - Mitsuba 3 (src/emitters/envmap.cpp, eval_spectrum with half_texel()): column x at
//    u = (x + ½)/W (periodic: the map is padded with a copy of column 0), row y at v = y/(H − 1),
//    so the first and last rows sit on the poles.
// Per axis a lattice coordinate a = t·scale − offset puts texel k at a = k; the radiance is
// Σ_k texel_k · hat(a − k) along each axis (hat(x) = max(0, 1 − |x|)), i.e. bilinear.
#pragma once

#include <algorithm>
#include <cmath>

namespace iris {

struct EnvmapAxis {
    int texels = 1;       // W or H
    float scale = 1.0f;   // a = t·scale − offset
    float offset = 0.0f;
    bool periodic = false;

    /// Texel index k (wrapped or clamped) for an integer lattice position.
    int texel(int k) const {
        if (periodic) return k >= 0 && k < texels ? k : ((k % texels) + texels) % texels;  // no division inside
        return std::clamp(k, 0, texels - 1);
    }
    /// The two texels around t and the weight of the second: value = (1 − f)·v[k0] + f·v[k1].
    void taps(float t, int& k0, int& k1, float& f) const {
        const float a = t * scale - offset;
        const float fl = std::floor(a);
        f = a - fl;
        k0 = texel(int(fl));
        k1 = texel(int(fl) + 1);
    }
};

/// Antiderivative of hat(x) = max(0, 1 − |x|).
inline double hatIntegral(double x) {
    if (x <= -1) return 0.0;
    if (x <= 0) return 0.5 * (x + 1) * (x + 1);
    if (x <= 1) return 1.0 - 0.5 * (1 - x) * (1 - x);
    return 1.0;
}

/// Calls visit(texel, weight) with the weights of the average of the interpolant over the
/// parameter interval [t0, t1] of `axis`: weight_k = (1/(a1 − a0)) ∫_{a0}^{a1} hat(a − k) da
/// (exact for the piecewise-linear interpolant; weights of a clamped or wrapped texel add up).
template <typename Visit>
void forEachAverageWeight(const EnvmapAxis& axis, double t0, double t1, Visit&& visit) {
    const double a0 = t0 * axis.scale - axis.offset, a1 = t1 * axis.scale - axis.offset;
    for (int k = int(std::floor(a0)) - 1; k <= int(std::ceil(a1)) + 1; ++k) {
        const double w = (hatIntegral(a1 - k) - hatIntegral(a0 - k)) / (a1 - a0);
        if (w > 0) visit(axis.texel(k), w);
    }
}

struct EnvmapLattice {
    EnvmapAxis u, v;
    int cellsV = 1;  // rows of the piecewise-constant sampling grid (its columns: u.texels)
    // Spectral mode: Mitsuba 3 (eval_spectrum) interpolates the normalised spectra and the scales
    // separately and multiplies them; Mitsuba 0.6 interpolates the spectra themselves.
    bool separateScale = false;

    static EnvmapLattice mitsuba06(int w, int h) {
        return {{w, float(w), 0.5f, true}, {h, float(h), 0.5f, false}, h, false};
    }
    static EnvmapLattice mitsuba3(int w, int h) {
        return {{w, float(w), 0.5f, true}, {h, float(h - 1), 0.0f, false}, h - 1, true};
    }
};

}  // namespace iris
