// Warping functions from the unit square to common domains, with their densities.
// Formulas: pbrt-v4 (Pharr, Jakob, Humphreys 2023) §A.5 unless noted.
#pragma once

#include <span>
#include <vector>

#include "core/math.h"

namespace iris {

/// Shirley-Chiu concentric map of the square to the unit disk (pbrt-v4 §A.5.1).
inline vec2 sampleUniformDiskConcentric(const vec2& u) {
    const vec2 o = 2.0f * u - vec2(1.0f);
    if (o.x == 0 && o.y == 0) return vec2(0.0f);
    float r, theta;
    if (std::abs(o.x) > std::abs(o.y)) {
        r = o.x;
        theta = kPiOver4 * (o.y / o.x);
    } else {
        r = o.y;
        theta = kPiOver2 - kPiOver4 * (o.x / o.y);
    }
    return r * vec2(std::cos(theta), std::sin(theta));
}

/// Malley's method: cosine-weighted hemisphere around +z, pdf = cosθ/π.
inline vec3 sampleCosineHemisphere(const vec2& u) {
    const vec2 d = sampleUniformDiskConcentric(u);
    const float z = safeSqrt(1.0f - d.x * d.x - d.y * d.y);
    return vec3(d.x, d.y, z);
}
inline float cosineHemispherePdf(float cosTheta) { return std::max(0.0f, cosTheta) * kInvPi; }

inline vec3 sampleUniformHemisphere(const vec2& u) {
    const float z = u.x;
    const float r = safeSqrt(1.0f - z * z);
    const float phi = 2.0f * kPi * u.y;
    return vec3(r * std::cos(phi), r * std::sin(phi), z);
}
inline float uniformHemispherePdf() { return kInv2Pi; }

inline vec3 sampleUniformSphere(const vec2& u) {
    const float z = 1.0f - 2.0f * u.x;
    const float r = safeSqrt(1.0f - z * z);
    const float phi = 2.0f * kPi * u.y;
    return vec3(r * std::cos(phi), r * std::sin(phi), z);
}
inline float uniformSpherePdf() { return kInv4Pi; }

/// Uniform direction in the cone of half-angle acos(cosThetaMax) around +z; pdf = 1/(2π(1−cosθmax)).
inline vec3 sampleUniformCone(const vec2& u, float cosThetaMax) {
    const float cosTheta = (1.0f - u.x) + u.x * cosThetaMax;
    const float sinTheta = safeSqrt(1.0f - cosTheta * cosTheta);
    const float phi = u.y * 2.0f * kPi;
    return vec3(std::cos(phi) * sinTheta, std::sin(phi) * sinTheta, cosTheta);
}
inline float uniformConePdf(float cosThetaMax) { return 1.0f / (2.0f * kPi * (1.0f - cosThetaMax)); }

/// Uniform barycentrics (b0, b1) on a triangle (Heitz 2019, "A Low-Distortion Map Between Triangle
/// and Square").
inline vec2 sampleUniformTriangle(const vec2& u) {
    float b0, b1;
    if (u.x < u.y) {
        b0 = u.x / 2;
        b1 = u.y - b0;
    } else {
        b1 = u.y / 2;
        b0 = u.x - b1;
    }
    return vec2(b0, b1);
}

/// Power heuristic with β = 2 (Veach 1997, eq. 9.13).
inline float powerHeuristic(float fPdf, float gPdf) {
    const float f = fPdf * fPdf, g = gPdf * gPdf;
    if (std::isinf(f)) return 1.0f;
    return f + g > 0 ? f / (f + g) : 0.0f;
}

/// Piecewise-constant 1D distribution over [0,1) (pbrt-v4 §A.4.1).
/// The CDF inversion uses a guide table (the "indexed search" of Chen & Asau 1974, Devroye 1986
/// §III.2.4): bucket b of [0,1) stores the CDF index range that can contain u ∈ [b/n, (b+1)/n), so
/// the binary search runs over a few entries instead of all n. It returns exactly the interval of
/// the plain binary search (findIntervalBinary); the samples do not change.
class Distribution1D {
public:
    Distribution1D() = default;
    explicit Distribution1D(std::span<const float> f);

    /// Continuous sample in [0,1); returns the density and the bin index.
    float sampleContinuous(float u, float* pdf, int* offset = nullptr) const;
    /// Discrete sample of a bin with probability f[i]/Σf.
    int sampleDiscrete(float u, float* pmf = nullptr, float* uRemapped = nullptr) const;
    float discretePmf(int i) const { return funcInt_ > 0 ? func_[i] / (funcInt_ * count()) : 0.0f; }
    float pdf(float x) const;
    int count() const { return int(func_.size()); }
    float integral() const { return funcInt_; }

    /// Index o of the interval with cdf[o] <= u < cdf[o+1] (clamped to [0, n−1]): guide table.
    int findInterval(float u) const;
    /// The same by a binary search over the whole CDF (the general path; for tests).
    int findIntervalBinary(float u) const;

private:
    std::vector<float> func_, cdf_;
    std::vector<int> guide_;  // n + 1 entries: guide_[b] = first CDF index > b/n
    float funcInt_ = 0;
};

/// Piecewise-constant 2D distribution on [0,1)^2, rows along v (pbrt-v4 §A.4.2).
class Distribution2D {
public:
    Distribution2D() = default;
    Distribution2D(std::span<const float> f, int nu, int nv);
    vec2 sampleContinuous(const vec2& u, float* pdf) const;
    /// Density at p: a read of a table filled at construction with the value of pdfGeneral.
    float pdf(const vec2& p) const;
    /// The density computed from the conditional and marginal distributions (for tests).
    float pdfGeneral(const vec2& p) const;

private:
    std::vector<Distribution1D> conditional_;
    Distribution1D marginal_;
    std::vector<float> pdf_;  // nu × nv, row-major in v
    int nu_ = 0, nv_ = 0;
};

}  // namespace iris
