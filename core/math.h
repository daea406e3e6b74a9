// Basic maths types and helpers shared by every module (GLM is the vector library).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

namespace iris {

using vec2 = glm::vec2;
using vec3 = glm::vec3;
using vec4 = glm::vec4;
using dvec3 = glm::dvec3;
using ivec2 = glm::ivec2;
using ivec3 = glm::ivec3;
using mat3 = glm::mat3;
using mat4 = glm::mat4;

constexpr float kPi = 3.14159265358979323846f;
constexpr float kInvPi = 0.31830988618379067154f;
constexpr float kInv2Pi = 0.15915494309189533577f;
constexpr float kInv4Pi = 0.07957747154594766788f;
constexpr float kPiOver2 = 1.57079632679489661923f;
constexpr float kPiOver4 = 0.78539816339744830961f;
constexpr float kOneMinusEpsilon = 0x1.fffffep-1f;

template <typename T>
inline T sqr(T x) { return x * x; }

inline float safeSqrt(float x) { return std::sqrt(std::max(0.0f, x)); }
inline double safeSqrt(double x) { return std::sqrt(std::max(0.0, x)); }
inline float safeAcos(float x) { return std::acos(std::clamp(x, -1.0f, 1.0f)); }
inline float safeAsin(float x) { return std::asin(std::clamp(x, -1.0f, 1.0f)); }

template <typename T>
inline T lerp(float t, const T& a, const T& b) { return (1 - t) * a + t * b; }

inline bool isFinite(const vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

/// Transform a point / direction by a 4x4 affine matrix.
inline vec3 transformPoint(const mat4& m, const vec3& p) { return vec3(m * vec4(p, 1.0f)); }
inline vec3 transformVector(const mat4& m, const vec3& v) { return mat3(m) * v; }
/// The matrix that carries normals under the affine map m: the inverse transpose of its linear
/// part, so that they stay perpendicular to transformed tangents (pbrt-v4 §3.10.3).
inline mat3 normalMatrix(const mat4& m) { return glm::transpose(glm::inverse(mat3(m))); }

/// The roots t0 ≤ t1 of a t² + 2 b t + c = 0 given its discriminant disc = b² − a c ≥ 0 (computed
/// by the caller in a form that does not cancel), as q/a and c/q with q = −(b + sign(b)·√disc), which
/// do not cancel when the roots differ greatly (Numerical Recipes §5.6; Haines et al. 2019, Ray
/// Tracing Gems ch. 7, eq. 7.4).
inline void stableQuadraticRoots(double a, double b, double c, double disc, double& t0, double& t1) {
    const double q = -(b + std::copysign(std::sqrt(disc), b));
    t0 = q / a;
    t1 = q != 0 ? c / q : t0;
    if (t0 > t1) std::swap(t0, t1);
}

}  // namespace iris
