// Mitsuba 0.6's "ldrfilm" output: exposure, then a tone map ("gamma": none; "reinhard": Reinhard,
// Stark, Shirley & Ferwerda, "Photographic Tone Reproduction for Digital Images", SIGGRAPH 2002,
// eq. 2–4, the global operator), then the transfer curve (gamma −1: the sRGB curve of IEC
// 61966-2-1; otherwise v^(1/gamma)), giving display code values in [0, 1].
#pragma once

#include <cstddef>
#include <string>

namespace iris {

struct LdrSettings {
    enum class Method { Gamma, Reinhard } method = Method::Gamma;
    float gamma = -1.0f;       // −1: sRGB transfer curve (Mitsuba's default)
    float exposure = 0.0f;     // stops: values are multiplied by 2^exposure
    float key = 0.18f;         // Reinhard's key value a (reinhardKey)
    float burn = 0.0f;         // reinhardBurn in [0, 1]: 0 = the brightest pixel maps to white
};

/// Tone map interleaved linear Rec.709 RGB in place into display code values.
void applyLdrTonemap(const LdrSettings& s, float* rgb, size_t pixelCount);

}  // namespace iris
