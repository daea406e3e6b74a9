// Orthonormal shading frame and the local-coordinate helpers used by every BSDF.
// Convention (as pbrt and Mitsuba): in the local frame the normal is +z, so cosθ = w.z.
#pragma once

#include "core/math.h"

namespace iris {

struct Frame {
    vec3 s{1, 0, 0}, t{0, 1, 0}, n{0, 0, 1};

    Frame() = default;
    Frame(const vec3& s_, const vec3& t_, const vec3& n_) : s(s_), t(t_), n(n_) {}

    /// Branchless orthonormal basis around a unit normal (Duff et al. 2017, "Building an
    /// Orthonormal Basis, Revisited", JCGT 6(1), Listing 3).
    static Frame fromNormal(const vec3& n) {
        const float sign = std::copysign(1.0f, n.z);
        const float a = -1.0f / (sign + n.z);
        const float b = n.x * n.y * a;
        return Frame(vec3(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x),
                     vec3(b, sign + n.y * n.y * a, -n.y), n);
    }

    /// Frame with normal n and first tangent as close as possible to `tangent` (Gram-Schmidt).
    static Frame fromNormalTangent(const vec3& n, const vec3& tangent) {
        vec3 s = tangent - n * glm::dot(n, tangent);
        const float len2 = glm::dot(s, s);
        if (!(len2 > 1e-12f)) return fromNormal(n);
        s /= std::sqrt(len2);
        return Frame(s, glm::cross(n, s), n);
    }

    vec3 toLocal(const vec3& v) const { return vec3(glm::dot(v, s), glm::dot(v, t), glm::dot(v, n)); }
    vec3 toWorld(const vec3& v) const { return s * v.x + t * v.y + n * v.z; }
};

// Spherical-coordinate helpers in the local frame (pbrt-v4 §9.1 conventions).
inline float cosTheta(const vec3& w) { return w.z; }
inline float cos2Theta(const vec3& w) { return w.z * w.z; }
inline float absCosTheta(const vec3& w) { return std::abs(w.z); }
inline float sin2Theta(const vec3& w) { return std::max(0.0f, 1.0f - cos2Theta(w)); }
inline float sinTheta(const vec3& w) { return std::sqrt(sin2Theta(w)); }
inline float tanTheta(const vec3& w) { return sinTheta(w) / cosTheta(w); }
inline float tan2Theta(const vec3& w) { return sin2Theta(w) / cos2Theta(w); }
inline float cosPhi(const vec3& w) {
    const float st = sinTheta(w);
    return st == 0 ? 1.0f : std::clamp(w.x / st, -1.0f, 1.0f);
}
inline float sinPhi(const vec3& w) {
    const float st = sinTheta(w);
    return st == 0 ? 0.0f : std::clamp(w.y / st, -1.0f, 1.0f);
}
inline bool sameHemisphere(const vec3& a, const vec3& b) { return a.z * b.z > 0; }

/// Mirror reflection of w about the local normal (0,0,1).
inline vec3 reflectLocal(const vec3& w) { return vec3(-w.x, -w.y, w.z); }
/// Mirror reflection of wo about an arbitrary unit normal n: 2(wo·n)n − wo.
inline vec3 reflect(const vec3& wo, const vec3& n) { return 2.0f * glm::dot(wo, n) * n - wo; }

}  // namespace iris
