// Parsing of the attribute strings of a Mitsuba scene file: numbers, lists, booleans, colours,
// spectra and the transform operations. Every function throws iris::Error at `loc` on bad input.
#pragma once

#include <string>
#include <vector>

#include "core/error.h"
#include "core/math.h"
#include "core/properties.h"

namespace iris {

float parseFloatValue(const std::string& s, const SourceLocation& loc);
int64_t parseIntValue(const std::string& s, const SourceLocation& loc);
bool parseBoolValue(const std::string& s, const SourceLocation& loc);
/// Numbers separated by commas and/or whitespace.
std::vector<float> parseFloatList(const std::string& s, const SourceLocation& loc);

/// "r, g, b" or a single value (replicated). With `srgb`, values (or "#rrggbb") are sRGB-encoded
/// and decoded to linear Rec.709 (IEC 61966-2-1 transfer function).
vec3 parseColorValue(const std::string& s, bool srgb, const SourceLocation& loc);

/// "<value>" (constant) or "λ1:v1, λ2:v2, ..." pairs (nm; commas or whitespace between pairs).
SpectrumValue parseSpectrumValue(const std::string& s, const SourceLocation& loc);


/// Mitsuba 0.6 parameter names to Mitsuba 3 names: "toWorld" → "to_world", "intIOR" → "int_ior".
std::string camelToSnake(const std::string& name);

}  // namespace iris
