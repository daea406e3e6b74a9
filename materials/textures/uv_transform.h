// The uv mapping of textures: Mitsuba 3's `to_uv` transform, uv' = (M · (u, v, 0, 1)).xy, followed
// by Mitsuba 0.6's `uscale`/`vscale`/`uoffset`/`voffset` (uv'' = uv' · scale + offset).
#pragma once

#include "core/math.h"
#include "core/properties.h"

namespace iris {

struct UVTransform {
    mat4 m{1.0f};
    vec2 scale{1.0f}, offset{0.0f};
    bool identity = true;

    explicit UVTransform(const Properties& p)
        : m(p.getTransform("to_uv")),
          scale(p.getFloat("uscale", 1.0f), p.getFloat("vscale", 1.0f)),
          offset(p.getFloat("uoffset", 0.0f), p.getFloat("voffset", 0.0f)),
          identity(m == mat4(1.0f) && scale == vec2(1.0f) && offset == vec2(0.0f)) {}

    vec2 apply(const vec2& uv) const {
        if (identity) return uv;
        return vec2(m * vec4(uv, 0.0f, 1.0f)) * scale + offset;
    }
};

}  // namespace iris
