// Four-lane access to a SampledSpectrum's storage (spectral/lanes.h), for the hot loops that work
// on spectra one group of SampledSpectrum::kLanes lanes at a time (Mueller matrices, Stokes rows):
// lanes l..l+3 loaded and stored, and which of them are entries rather than padding.
#pragma once

#include <cstdint>

#include "spectral/lanes.h"
#include "spectral/sampled_spectrum.h"

namespace iris::lanes {

static_assert(SampledSpectrum::kLanes == 4, "a group of lanes is one Float4");

/// Lanes l..l+3 of s (l a multiple of 4, below s.padded()).
IRIS_LANES_INLINE Float4 loadGroup(const SampledSpectrum& s, int l) { return load(s.lanes() + l); }
IRIS_LANES_INLINE void storeGroup(SampledSpectrum& s, int l, Float4 v) { store(s.lanes() + l, v); }
/// True in lane i where l + i < n: the lanes of group l that are entries of an n-entry spectrum.
IRIS_LANES_INLINE Int4 entryLanes(int l, int n) { return Int4{0, 1, 2, 3} + l < broadcast(int32_t(n)); }

}  // namespace iris::lanes
