// Diffuse area light attached to a shape (Mitsuba "area" emitter): uniform radiance on the side
// the surface normal points to. Meshes and cylinders are sampled uniformly by area (a cylinder as
// Mitsuba 3's sample_position: φ and the axial position uniform); spheres by the cone of
// directions they subtend (pbrt-v4 §6.2.4). The radiance may be a texture over the shape's uv
// (Mitsuba's area emitter with a textured `radiance`), looked up at the hit's or the sampled
// point's uv (and, on meshes, triangle and barycentrics, for `mesh_attribute`); sampling stays
// uniform by area (Mitsuba 3 importance-samples such a texture through the shape's
// parametrisation: same expectation, other variance).
#pragma once

#include <vector>

#include "render/lights/light.h"
#include "core/mesh.h"
#include "core/sampling.h"
#include "materials/textures/texture.h"
#include "core/cylinder_intersection.h"
#include "core/sphere_intersection.h"
#include "spectral/spectrum.h"

namespace iris {

class AreaLight final : public Light {
public:
    /// Mesh emitter (mesh in world space; must outlive the light).
    AreaLight(const TriangleMesh* mesh, SpectrumTexturePtr radiance);
    /// Sphere emitter with its local axes `frame` (for uv); `inward` when its normals are flipped.
    AreaLight(const vec3& center, float radius, const mat3& frame, bool inward, SpectrumTexturePtr radiance);
    /// Open cylinder emitter (world space); `inward` when its normals are flipped.
    AreaLight(const CylinderGeometry& cylinder, float radius, bool inward, SpectrumTexturePtr radiance);

    Type type() const override { return Type::Area; }
    std::optional<LightSample> sampleLi(const vec3& p, const vec2& u, const SampledWavelengths& wl) const override;
    float pdfLi(const vec3& p, const vec3& wi, const SurfaceInteraction* hit) const override;
    SampledSpectrum Le(const TextureQuery& at, const vec3& n, const vec3& w, const SampledWavelengths& wl) const override;
    /// A point uniform in area and a cosine-weighted direction on the emitting side (pbrt-v4
    /// §12.3 DiffuseAreaLight::SampleLe): pdfPos = 1/area, pdfDir = cosθ/π.
    std::optional<LightEmission> sampleLe(const vec2& uPos, const vec2& uDir, const SampledWavelengths& wl,
                                          const SceneBounds& bounds) const override;
    vec2 pdfLe(const vec3& p, const vec3& n, const vec3& w, const SceneBounds& bounds) const override;
    float area() const { return area_; }

private:
    /// Uniform area sample of the mesh or cylinder: the point as a texture sees it (position, uv;
    /// on meshes the triangle and barycentrics) and the normal.
    void sampleArea(const vec2& u, TextureQuery& at, vec3& n) const;

    enum class Kind { Mesh, Sphere, Cylinder } kind_;
    const TriangleMesh* mesh_ = nullptr;
    Distribution1D triangles_;
    CylinderGeometry cylinder_;
    vec3 center_{0.0f};
    float radius_ = 0.0f;
    mat3 frame_{1.0f};  // sphere: object-space axes
    bool inward_ = false;
    float area_ = 0.0f;
    SpectrumTexturePtr radiance_;
};

}  // namespace iris
