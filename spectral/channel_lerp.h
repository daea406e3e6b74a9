// Piecewise-linear interpolation through three (λ, value) points: a parameter given per RGB channel
// at the wavelengths the channels stand for, read at any wavelength in spectral mode (constant
// outside the channel wavelengths' range; the spectral reading of the thesis' per-channel η_t,
// thesis 000 §2.4 / §3.2, see materials/thesis/thesis_channels.h). The one interpolation of per-channel
// indices: IOR::perChannel (spectral/ior.h) uses it for every material.
// The points are sorted once, when the parameter is read, not at every evaluation. Between two
// equal neighbours it returns their value exactly ((1 − t)a + ta may differ from a by rounding,
// which made e.g. an index of 1.4 in all three channels look dispersive).
#pragma once

#include <algorithm>
#include <array>
#include <utility>

#include "core/math.h"

namespace iris {

class ChannelLerp {
public:
    ChannelLerp() = default;
    ChannelLerp(const vec3& values, const vec3& lambdas) {
        std::array<std::pair<float, float>, 3> pts{
            {{lambdas[0], values[0]}, {lambdas[1], values[1]}, {lambdas[2], values[2]}}};
        std::sort(pts.begin(), pts.end());  // by λ (ties by value)
        for (int i = 0; i < 3; ++i) {
            l_[i] = pts[i].first;
            v_[i] = pts[i].second;
        }
    }

    float operator()(float lambda) const {
        if (lambda <= l_[0]) return v_[0];
        if (lambda >= l_[2]) return v_[2];
        const int k = lambda <= l_[1] ? 0 : 1;
        const float span = l_[k + 1] - l_[k];
        if (!(span > 0) || v_[k] == v_[k + 1]) return v_[k + 1];
        return lerp((lambda - l_[k]) / span, v_[k], v_[k + 1]);
    }

private:
    float l_[3] = {0, 0, 0}, v_[3] = {0, 0, 0};
};

}  // namespace iris
