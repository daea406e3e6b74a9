// Samplers (Mitsuba's <sampler>): iris draws every sample from its own per-pixel PCG32 streams
// (render/renderer.h), so a sampler plugin gives only the number of samples per pixel.
#pragma once

#include "core/registry.h"

namespace iris {

struct SamplerDescription {
    int sampleCount = 4;  // Mitsuba's default sample_count
};

using SamplerRegistry = Registry<SamplerDescription>;

}  // namespace iris
