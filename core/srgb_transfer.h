// The sRGB transfer function (IEC 61966-2-1): 8- and 16-bit sRGB code values to linear Rec.709.
// Used wherever sRGB-encoded values enter: XML colours marked srgb, bitmap textures, PLY vertex
// colours, glTF colour textures.
#pragma once

#include <cmath>

namespace iris {

/// sRGB electro-optical transfer function: code value in [0, 1] → linear (IEC 61966-2-1 eq. 1).
inline float srgbToLinear(float v) { return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f); }

}  // namespace iris
