// The scalar terms of the glTF 2.0 metallic-roughness BRDF and of its Khronos extensions, as the
// specifications write them (glTF 2.0 Appendix B "BRDF Implementation"; KHR_materials_sheen,
// "Sheen BRDF"). All in the local shading frame (normal +z); α is the squared perceptual roughness.
#pragma once

#include "core/math.h"

namespace iris::gltf {

/// Trowbridge-Reitz (GGX) D(h) = α² χ⁺(n·h) / (π ((n·h)²(α² − 1) + 1)²)  (Appendix B.3.2), for a
/// unit half vector h, whose (n·h)²(α² − 1) + 1 is evaluated as h.x² + h.y² + α² h.z² (the same
/// value without the cancellation of 1 − (n·h)² in float when α² is below its precision).
float ggxD(float alpha, const vec3& h);

/// The separable Smith visibility V = G/(4 |n·l| |n·v|) with
/// G = G1(l) G1(v), G1(x) = 2|n·x| / (|n·x| + sqrt(α² + (1 − α²)(n·x)²))  (Appendix B.3.2).
float ggxV(float alpha, float cosL, float cosV);

/// specular_brdf(α) = V · D at the half vector h of (l, v) (Appendix B.3.2), for l, v above.
float specularBrdf(float alpha, const vec3& l, const vec3& v);

/// Schlick's (1 − |v·h|)⁵ weight (Appendix B.3.4).
float schlickWeight(float vDotH);

/// KHR_materials_volume "Implementation": the Schlick weight (1 − |cos θ|)⁵ at the dense side of a
/// volume boundary, where eta = η_o / η_i is the index beyond the surface over the viewer's:
/// eta ≥ 1, θ is the viewer's angle to h (case 1); eta < 1, the transmitted angle,
/// sin²θ_o = (1 − (v·h)²) / eta² (case 2); −1 for total internal reflection, F = 1 (case 3).
float volumeSchlickWeight(float vDotH, float eta);

/// "Charlie" sheen distribution D = (2 + 1/α) sin(θh)^(1/α) / (2π) (KHR_materials_sheen; Estevez &
/// Kulla 2017 eq. 2). α = sheenRoughness², clamped below at kMinSheenAlpha.
float charlieD(float alpha, float cosH);
/// Sheen visibility V = 1 / ((1 + Λ(n·v) + Λ(n·l)) 4 (n·v)(n·l)) with Estevez & Kulla's fit of Λ
/// (KHR_materials_sheen, "Sheen visibility"; coefficients interpolated by (1 − α)²).
float charlieV(float alpha, float cosL, float cosV);
/// sheen_brdf without its colour: D · V at h of (l, v).
float sheenBrdf(float alpha, const vec3& l, const vec3& v);
/// The smallest sheen α used: sheenRoughness² below this is raised to it (the spec's D has no
/// limit at α = 0; the albedo table starts here).
constexpr float kMinSheenAlpha = 0.07f * 0.07f;

/// E(cosθ): the directional albedo ∫ sheenBrdf cosθl dωl of the uncoloured Charlie lobe at view
/// cosine `cosV` and sheen roughness (perceptual): KHR_materials_sheen's "albedo scaling" term.
/// Computed once by quadrature of sheenBrdf on a 32 × 32 grid of (cosV, roughness) and
/// interpolated bilinearly.
float sheenAlbedo(float cosV, float sheenRoughness);

}  // namespace iris::gltf
