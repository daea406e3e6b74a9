// Directional albedo ρ(ωo) = ∫ f(ωo, ωi) |cosθi| dωi of a BSDF (the white-furnace quantity): the
// mean of the BSDF's own sample weights f |cosθi| / pdf over many samples (Monte Carlo estimator
// of the integral, e.g. pbrt-v4 §4.3.2 "hemispherical-directional reflectance"), per path entry,
// with its standard error. Used by the material tests, the material_albedo tables of the docs and
// anyone checking energy conservation.
#pragma once

#include <cstdint>
#include <vector>

#include "materials/bsdf.h"

namespace iris {

struct AlbedoEstimate {
    double mean = 0, stderr_ = 0;  // estimate and one standard error of it
};

/// Mean and standard error of n values given their sum and sum of squares.
AlbedoEstimate albedoFromSums(double sum, double sumSq, int n);

/// Directional albedo per entry of the BSDF's spectra (reflection and transmission together),
/// from `samples` BSDF samples drawn with a PCG32 stream fixed by `seed` (repeatable bit for bit).
std::vector<AlbedoEstimate> directionalAlbedo(const BSDF& bsdf, const vec3& wo, int samples, uint64_t seed,
                                              TransportMode mode = TransportMode::Radiance);

}  // namespace iris
