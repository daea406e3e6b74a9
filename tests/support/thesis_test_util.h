// Helpers shared by the tests of the thesis' models (granier, proposed, rough plastic).
#pragma once

#include <gtest/gtest.h>

#include <cmath>

#include "core/rng.h"
#include "core/sampling.h"
#include "materials/bsdf.h"
#include "spectral/wavelengths.h"

namespace iris::test {

/// Spectral-mode wavelengths (N = 1) at exactly `lambda`: searches the primary sample u of
/// SampledWavelengths::sampleUniform whose float result is exactly lambda.
inline SampledWavelengths exactWavelength(float lambda) {
    float u = (lambda - kLambdaMin) / (kLambdaMax - kLambdaMin);
    for (int step = 0; step < 64; ++step) {
        const SampledWavelengths wl = SampledWavelengths::sampleUniform(u, 1);
        if (wl.lambda(0) == lambda) return wl;
        u = std::nextafter(u, wl.lambda(0) < lambda ? 2.0f : -1.0f);
    }
    ADD_FAILURE() << "no primary sample gives exactly " << lambda << " nm";
    return SampledWavelengths::sampleUniform(u, 1);
}

/// ∫ pdf(wo, wi) over the upper hemisphere by a fine midpoint rule (θ × φ = nt × 2nt cells).
inline double upperPdfMass(const BSDF& bsdf, const vec3& wo, int nt = 1500) {
    const int np = 2 * nt;
    double mass = 0;
    for (int i = 0; i < nt; ++i) {
        const double th = (i + 0.5) * (M_PI / 2) / nt;
        for (int j = 0; j < np; ++j) {
            const double ph = (j + 0.5) * 2 * M_PI / np;
            const vec3 w(float(std::sin(th) * std::cos(ph)), float(std::sin(th) * std::sin(ph)), float(std::cos(th)));
            mass += bsdf.pdf(wo, w, TransportMode::Radiance) * std::sin(th);
        }
    }
    return mass * (M_PI / 2 / nt) * (2 * M_PI / np);
}

/// Fraction of sample() calls that return a direction (fixed seed), and its standard error.
inline std::pair<double, double> acceptedFraction(const BSDF& bsdf, const vec3& wo, int n = 400000, uint64_t seed = 9) {
    Sampler rng(seed);
    int accepted = 0;
    for (int i = 0; i < n; ++i) {
        const float uc = rng.get1D();
        if (bsdf.sample(wo, uc, rng.get2D(), TransportMode::Radiance)) ++accepted;
    }
    const double f = double(accepted) / n;
    return {f, std::sqrt(f * (1 - f) / n)};
}

}  // namespace iris::test
