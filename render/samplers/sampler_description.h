// Samplers (Mitsuba's <sampler>): the number of samples per pixel and the sequence the renderer
// draws each sample's points from (core/sample_sequences.h, core/rng.h's Sampler).
#pragma once

#include <string>

#include "core/registry.h"
#include "core/rng.h"

namespace iris {

struct SamplerDescription {
    int sampleCount = 4;    // Mitsuba's default sample_count
    SamplePattern pattern;  // its size is set by the renderer (RenderOptions::patternSize)
};

using SamplerRegistry = Registry<SamplerDescription>;

/// The sequences by the names of the samplers that draw them: "independent", "stratified",
/// "multijitter", "sobol", "highdimsobol" (the names --sampler and the Python module accept).
SampleSequence sampleSequenceNamed(const std::string& name);
const char* sampleSequenceName(SampleSequence s);

}  // namespace iris
