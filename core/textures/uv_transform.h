// The `to_uv` transform of textures (Mitsuba): uv' = (M · (u, v, 0, 1)).xy.
#pragma once

#include "core/math.h"
#include "core/properties.h"

namespace iris {

struct UVTransform {
    mat4 m{1.0f};
    bool identity = true;

    explicit UVTransform(const Properties& p) : m(p.getTransform("to_uv")), identity(m == mat4(1.0f)) {}
    vec2 apply(const vec2& uv) const { return identity ? uv : vec2(m * vec4(uv, 0.0f, 1.0f)); }
};

}  // namespace iris
