// A vertex of a BDPT subpath (Veach 1997 ch. 10; pbrt-v4 §13.x "Vertex"): the camera, a light, or a
// surface point, with the throughput β of the subpath that reaches it and the two area densities
// MIS needs: pdfFwd, of sampling it from its predecessor on its own subpath, and pdfRev, of sampling
// it from its successor as the other subpath would. Lights at infinity (a camera ray that escaped,
// or an environment or directional light's ray) have their densities in solid angle.
#pragma once

#include "materials/bsdf.h"
#include "materials/material.h"
#include "render/lights/light.h"
#include "render/scene.h"

namespace iris {

enum class BDPTVertexType { Camera, Light, Surface };

struct BDPTVertex {
    BDPTVertexType type = BDPTVertexType::Surface;
    SampledSpectrum beta;
    vec3 p{0.0f};
    vec3 ng{0.0f};              // geometric normal; 0 for points not on a surface (pinhole, point light)
    Frame shading;              // surface vertices: the BSDF's frame
    SurfaceInteraction si;      // surface vertices: the hit (emission lookups, ray offsets)
    const BSDF* bsdf = nullptr; // surface vertices
    const Light* light = nullptr;  // light vertices (nullptr: a camera ray that escaped)
    bool delta = false;         // sampled by a delta lobe: cannot be connected or reweighted
    bool infinite = false;      // a light vertex at infinity (p is then a point along its direction)
    float pdfFwd = 0.0f, pdfRev = 0.0f;

    bool onSurface() const { return glm::dot(ng, ng) > 0; }
    /// Can a connection end here (pbrt-v4 Vertex::IsConnectible)?
    bool connectible() const;
    /// An emitter: a light vertex or a surface with an area light.
    bool isLight() const { return type == BDPTVertexType::Light || (type == BDPTVertexType::Surface && si.areaLight); }
    bool isDeltaLight() const { return type == BDPTVertexType::Light && light && light->isDelta(); }
    bool isInfiniteLight() const { return type == BDPTVertexType::Light && infinite; }
    /// |cos| at this vertex of direction w with the shading normal (1 off surfaces).
    float absCosShading(const vec3& w) const;
};

/// A surface vertex for hit `si` with its BSDF, reached with throughput β from `prev` by a
/// direction of solid-angle density pdf.
BDPTVertex surfaceVertex(const SurfaceInteraction& si, const Frame& shading, const BSDF* bsdf, const SampledSpectrum& beta,
                         float pdf, const BDPTVertex& prev);
/// The light at infinity a camera ray along `ray` escaped to, reached with β and density pdf.
BDPTVertex escapedVertex(const Ray& ray, const SampledSpectrum& beta, float pdf);

/// The BSDF value f(this → next) with this vertex's direction to its predecessor as wo (no cosine).
SampledSpectrum vertexF(const BDPTVertex& v, const BDPTVertex& next, TransportMode mode);

/// A solid-angle density at `from` for the direction to `to`, as an area density at `to` (a solid
/// angle one for lights at infinity) (pbrt-v4 Vertex::ConvertDensity).
float convertDensity(const BDPTVertex& from, float pdf, const BDPTVertex& to);

/// The area density with which v samples `next`, given its predecessor `prev` (nullptr for the
/// camera) (pbrt-v4 Vertex::PDF).
float vertexPdf(const Scene& scene, const BDPTVertex& v, const BDPTVertex* prev, const BDPTVertex& next);
/// The area density with which light vertex (or emitting surface) v emits towards `next`
/// (pbrt-v4 Vertex::PDFLight).
float lightPdf(const Scene& scene, const BDPTVertex& v, const BDPTVertex& next);
/// The density with which a light subpath starts at emitter v (towards `next`): the light's choice
/// times its position density, or for lights at infinity the directional density of every
/// infinite light (pbrt-v4 Vertex::PDFLightOrigin, InfiniteLightDensity).
float lightOriginPdf(const Scene& scene, const BDPTVertex& v, const BDPTVertex& next);

/// Σ over the infinite lights of their choice's pmf times their directional density towards wi
/// (pbrt-v4 InfiniteLightDensity).
float infiniteLightDensity(const Scene& scene, const vec3& wi);

/// The radiance emitter v sends towards `to` (pbrt-v4 Vertex::Le): the area light of its surface,
/// or, at infinity, every infinite light along the direction.
SampledSpectrum vertexLe(const Scene& scene, const BDPTVertex& v, const BDPTVertex& to, const SampledWavelengths& wl);

}  // namespace iris
