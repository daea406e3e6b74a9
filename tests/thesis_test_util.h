// Helpers shared by the tests of the thesis' models (granier, proposed, rough plastic).
#pragma once

#include <gtest/gtest.h>

#include "core/rng.h"
#include "core/sampling.h"
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

}  // namespace iris::test
