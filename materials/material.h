// A material turns the textures and spectra a scene gives it into a BSDF at one surface point
// and for one set of wavelengths. BSDFs live in the per-thread Arena for one path sample.
#pragma once

#include <memory>

#include "core/arena.h"
#include "core/frame.h"
#include "core/ray.h"
#include "core/registry.h"
#include "materials/textures/texture.h"
#include "materials/bsdf.h"
#include "spectral/wavelengths.h"

namespace iris {

/// What a material knows about the surface point.
struct ShadingPoint {
    TextureQuery tex;       // uv and position for texture lookups
    Frame shading;          // shading frame (smooth normal, tangent from dp/du when available)
    vec3 ng{0, 0, 1};       // geometric normal (world)
    vec3 dpdu{1, 0, 0};     // ∂p/∂u (world), for anisotropy and bump maps
    vec3 dpdv{0, 1, 0};     // ∂p/∂v (world), for bump maps
};

class Material {
public:
    virtual ~Material() = default;

    /// BSDF at this point for these wavelengths. A material whose parameters vary with wavelength
    /// in a way that makes directions wavelength-dependent (dispersive refraction) calls
    /// wl.terminateSecondary(). Returns nullptr for a surface that only marks a boundary.
    virtual const BSDF* getBSDF(const ShadingPoint& sp, SampledWavelengths& wl, Arena& arena) const = 0;

    /// Optional perturbation of the shading frame (normal / bump mapping, thesis' tilted n0).
    /// The default returns the frame unchanged.
    virtual Frame shadingFrame(const ShadingPoint& sp) const { return sp.shading; }

    /// True when getBSDF depends on ShadingPoint::shading (the normal/bump-map wrappers, which
    /// perturb it inside their BSDF; materials/perturbed_frame.h), so that a wrapper around such a
    /// material hands it each frame it may use.
    virtual bool perturbsShading() const { return false; }

    /// True when the material's BSDFs may let shadow rays through (a pass-through lobe with
    /// BSDF::nullTransmission: `null`, `mask`, `thindielectric`); the volumetric integrators build
    /// the BSDF of such a surface on a shadow ray and stop at any other (integrators/volpath.cpp).
    virtual bool transmitsShadowRays() const { return false; }
};

/// Where a surface hit looks up textures: uv, position and, on meshes, the triangle and barycentrics
/// (the materials' lookups and an area emitter's radiance at the hit).
inline TextureQuery textureQueryAt(const SurfaceInteraction& si) {
    TextureQuery q;
    q.uv = si.uv;
    q.p = si.p;
    q.mesh = si.mesh;
    q.triangle = si.triangle;
    q.bary = si.bary;
    return q;
}

/// The shading point of a surface hit as the integrators give it to its material: uv, position,
/// the derivatives with their lengths, and the shading frame (smooth normal, tangent ∂p/∂u) after
/// the material's own perturbation (Material::shadingFrame).
inline ShadingPoint shadingPointAt(const SurfaceInteraction& si) {
    ShadingPoint sp;
    sp.tex = textureQueryAt(si);
    sp.ng = si.ng;
    sp.dpdu = si.dpScale * si.dpdu;
    sp.dpdv = si.dpScale * si.dpdv;
    sp.shading = Frame::fromNormalTangent(si.ns, si.dpdu);
    sp.shading = si.material->shadingFrame(sp);
    return sp;
}

using MaterialPtr = std::shared_ptr<const Material>;
/// Every BSDF type, by its scene-file name (`<bsdf type="...">`).
using MaterialRegistry = Registry<Material>;

}  // namespace iris
