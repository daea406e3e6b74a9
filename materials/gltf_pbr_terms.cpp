#include "materials/gltf_pbr_terms.h"

#include "materials/cloth_distributions.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace iris::gltf {

float ggxD(float alpha, const vec3& h) {
    if (h.z <= 0) return 0.0f;  // χ⁺(n·h)
    const float a2 = alpha * alpha;
    const float d = h.x * h.x + h.y * h.y + a2 * h.z * h.z;  // = (n·h)²(α² − 1) + 1 for |h| = 1
    return a2 / (kPi * d * d);  // Appendix B.3.2, microfacet distribution
}

float ggxV(float alpha, float cosL, float cosV) {
    const float a2 = alpha * alpha;
    const float l = std::abs(cosL), v = std::abs(cosV);
    if (l == 0 || v == 0) return 0.0f;
    // Appendix B.3.2: V = G / (4|N·L||N·V|) with the separable Smith-GGX G; the 2|N·x| of each G1
    // cancels against the 4|N·L||N·V|.
    const float gl = l + std::sqrt(a2 + (1.0f - a2) * l * l);
    const float gv = v + std::sqrt(a2 + (1.0f - a2) * v * v);
    return 1.0f / (gl * gv);
}

float specularBrdf(float alpha, const vec3& l, const vec3& v) {
    const vec3 h = glm::normalize(l + v);
    return ggxV(alpha, l.z, v.z) * ggxD(alpha, h);
}

float schlickWeight(float vDotH) {
    const float m = std::clamp(1.0f - std::abs(vDotH), 0.0f, 1.0f);
    const float m2 = m * m;
    return m2 * m2 * m;  // Appendix B.3.4: F = F0 + (1 − F0)(1 − |V·H|)⁵
}

float volumeSchlickWeight(float vDotH, float eta) {
    if (eta >= 1.0f) return schlickWeight(vDotH);  // case 1: F⁺ = f0 + (1 − f0)(1 − |V·H|)⁵
    const float sin2o = (1.0f - vDotH * vDotH) / (eta * eta);  // case 2: sin²θo = (ηi/ηo)² (1 − (V·H)²)
    if (sin2o >= 1.0f) return -1.0f;  // case 3: total internal reflection, F = 1
    return schlickWeight(std::sqrt(1.0f - sin2o));
}

float charlieD(float alpha, float cosH) { return cloth::charlieD(std::max(alpha, kMinSheenAlpha), cosH); }

namespace {

constexpr int kTable = 32;

using AlbedoTable = std::array<float, kTable * kTable>;

/// ∫ sheenBrdf cosθl dωl by a midpoint rule in (cosθl, φl): 128 × 64 cells.
float integrateAlbedo(float cosV, float roughness) {
    const float alpha = std::max(roughness * roughness, kMinSheenAlpha);
    const vec3 v(std::sqrt(std::max(0.0f, 1.0f - cosV * cosV)), 0.0f, cosV);
    constexpr int nMu = 128, nPhi = 64;
    double sum = 0;
    for (int i = 0; i < nMu; ++i) {
        const float mu = (i + 0.5f) / nMu;
        const float s = std::sqrt(std::max(0.0f, 1.0f - mu * mu));
        for (int j = 0; j < nPhi; ++j) {
            const float phi = kPi * (j + 0.5f) / nPhi;  // symmetric in φ: half the circle, doubled
            const vec3 l(s * std::cos(phi), s * std::sin(phi), mu);
            sum += double(sheenBrdf(alpha, l, v)) * mu;
        }
    }
    return float(sum * (1.0 / nMu) * (2.0 * kPi / nPhi));
}

const AlbedoTable& albedoTable() {
    static const AlbedoTable table = [] {
        AlbedoTable t{};
        for (int r = 0; r < kTable; ++r)
            for (int m = 0; m < kTable; ++m)
                t[size_t(r * kTable + m)] = integrateAlbedo(std::max(m / float(kTable - 1), 1e-3f), r / float(kTable - 1));
        return t;
    }();
    return table;
}

}  // namespace

float charlieV(float alpha, float cosL, float cosV) {
    alpha = std::max(alpha, kMinSheenAlpha);
    const float l = std::min(std::abs(cosL), 1.0f), v = std::min(std::abs(cosV), 1.0f);  // Λ's fit needs 1 − cos ≥ 0
    if (l == 0 || v == 0) return 0.0f;
    // KHR_materials_sheen "Sheen visibility": the height-correlated G of the Estevez-Kulla Λ fit
    // (materials/cloth_distributions.h, shared with the cloth material) over 4 (n·v)(n·l).
    return cloth::charlieG(v, l, alpha) / (4.0f * v * l);
}

float sheenBrdf(float alpha, const vec3& l, const vec3& v) {
    const vec3 h = glm::normalize(l + v);
    return charlieD(alpha, h.z) * charlieV(alpha, l.z, v.z);
}

float sheenAlbedo(float cosV, float sheenRoughness) {
    const AlbedoTable& t = albedoTable();
    const float x = std::clamp(cosV, 0.0f, 1.0f) * (kTable - 1), y = std::clamp(sheenRoughness, 0.0f, 1.0f) * (kTable - 1);
    const int x0 = std::min(int(x), kTable - 2), y0 = std::min(int(y), kTable - 2);
    const float fx = x - x0, fy = y - y0;
    auto at = [&](int r, int m) { return t[size_t(r * kTable + m)]; };
    const float lo = at(y0, x0) * (1 - fx) + at(y0, x0 + 1) * fx, hi = at(y0 + 1, x0) * (1 - fx) + at(y0 + 1, x0 + 1) * fx;
    return lo * (1 - fy) + hi * fy;
}

}  // namespace iris::gltf
