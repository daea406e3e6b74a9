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
    /// A gradient with respect to the transformed uv' as one with respect to uv: Jᵀ g, where
    /// J = ∂uv'/∂uv = diag(scale) · (upper-left 2×2 of m) (Mitsuba 3 bitmap.cpp eval_1_grad
    /// multiplies by the transposed to_uv matrix the same way).
    vec2 pullBack(const vec2& g) const {
        if (identity) return g;
        const vec2 gs = g * scale;  // gradient wrt (m · uv).xy
        // glm is column-major: m[c][r]; (Jᵀ g)_c = Σ_r m[c][r] gs_r.
        return vec2(m[0][0] * gs.x + m[0][1] * gs.y, m[1][0] * gs.x + m[1][1] * gs.y);
    }
};

}  // namespace iris
