// A `<spectrum value="λ:v, λ:v, ...">` value as the XML reader parses it, for tests that set one
// on Properties.
#pragma once

#include <utility>
#include <vector>

#include "core/properties.h"

namespace iris::test {

inline SpectrumValue spectrumPairs(std::vector<float> lambdas, std::vector<float> values) {
    SpectrumValue v;
    v.type = SpectrumValue::Type::Pairs;
    v.lambdas = std::move(lambdas);
    v.values = std::move(values);
    return v;
}

}  // namespace iris::test
