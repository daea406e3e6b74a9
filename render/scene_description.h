// Everything a scene file describes: the scene loader (render/loader/) fills it with the objects
// the plugin registries created, and Scene's constructor (render/scene.cpp) turns it into Embree
// geometry and the light list. Units: scene units for lengths; radiance
// in the relative units of docs/conventions.md.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/math.h"
#include "core/memory_budget.h"
#include "core/mesh.h"
#include "core/rng.h"
#include "materials/material.h"
#include "media/medium.h"
#include "render/films/ldr_tonemap.h"
#include "render/scene_defaults.h"
#include "render/filters/rfilter.h"
#include "core/cylinder_intersection.h"
#include "core/sdf_grid.h"
#include "render/sensors/sensor.h"
#include "spectral/spectrum.h"

namespace iris {

class Light;

struct ShapeDescription {
    enum class Type { Mesh, Sphere, Cylinder, SdfGrid } type = Type::Mesh;
    // World space for a top-level shape, the group's space for a shape of a ShapeGroupDescription.
    std::shared_ptr<TriangleMesh> mesh;  // Mesh: already transformed by the shape's to_world
    vec3 center{0.0f};                   // Sphere
    mat3 frame{1.0f};                    // Sphere: its local axes (to_world's rotation), for uv and tangents
    bool rotated = false;                // Sphere: frame is not the identity
    float radius = 1.0f;                 // Sphere, Cylinder
    CylinderGeometry cylinder;           // Cylinder (world space)
    std::shared_ptr<const SdfGrid> sdf;  // SdfGrid (placed in the shape's space by its toWorld)
    bool flipNormals = false;            // Sphere, Cylinder: normals point inwards
    bool faceNormals = false;            // Mesh: ignore vertex normals
    MaterialPtr material;                // nullptr: the default diffuse (0.5) material
    SpectrumPtr emission;                // area emitter radiance (Illuminant kind), or nullptr
    SpectrumTexturePtr emissionTexture;  // a textured area emitter radiance (then emission is nullptr)
    // Participating media on the two sides (Mitsuba's `interior` and `exterior`), or nullptr for
    // vacuum / "no change"; a shape with either is a medium transition (integrators/volpath.cpp).
    MediumPtr interior, exterior;
    std::string name;                    // for messages
};

/// A Mitsuba `shapegroup` (Mitsuba 3, src/render/shapegroup.cpp): shapes in the group's own space
/// (meshes already transformed by their own to_world into it) that are not rendered themselves,
/// only through instances. Holds no emitters, groups or instances (Mitsuba 3 refuses them).
struct ShapeGroupDescription {
    std::string name;  // the group's id, for messages
    std::vector<ShapeDescription> shapes;
};

/// A Mitsuba `instance` (Mitsuba 3, src/shapes/instance.cpp): a shape group placed in the world by
/// `toWorld`, which composes with the group's shapes' own to_world (world = toWorld · shape to_world).
struct InstanceDescription {
    std::shared_ptr<const ShapeGroupDescription> group;  // shared by every instance of one id
    mat4 toWorld{1.0f};
    std::string name;  // for messages
};

/// The sensor with its film: image size, reconstruction filter, and the sensor plugin bound to
/// that size.
struct CameraDescription {
    int width = 512, height = 512;
    ReconstructionFilterPtr filter;  // nullptr: Mitsuba's default, a gaussian of stddev 0.5 px
    SensorPtr sensor;                // created for width × height (render/sensors/)
    std::optional<LdrSettings> ldr;  // an ldrfilm's tone mapping for the PNG (render/films/)
    MediumPtr medium;                // the medium the sensor is in (nullptr: vacuum)
};

class Integrator;
using IntegratorPtr = std::shared_ptr<const Integrator>;

struct SceneDescription {
    std::string sourceFile;  // for messages and metadata
    std::vector<ShapeDescription> shapes;
    std::vector<InstanceDescription> instances;  // placed shape groups (Scene: Embree instances)
    std::vector<std::shared_ptr<Light>> lights;  // non-area lights (point, spot, env, ...)
    CameraDescription camera;
    IntegratorPtr integrator;  // render/integrator.h; the loader gives kDefaultIntegrator (render/scene_defaults.h) when the scene names none
    int spp = kDefaultSampleCount;  // sampler sample_count
    // The sampler's sequence (render/samplers/); its pattern size is set by the renderer.
    std::string samplerName = kDefaultSampler;
    SamplePattern samplePattern;
    // What the loader charged to the memory budget for this scene, given back when the last copy goes.
    std::shared_ptr<const MemoryReservation> memory;
    /// True when some shape or the sensor has a medium (only the volumetric integrators render it).
    bool hasMedia() const {
        if (camera.medium) return true;
        for (const ShapeDescription& s : shapes)
            if (s.interior || s.exterior) return true;
        for (const InstanceDescription& i : instances)
            for (const ShapeDescription& s : i.group->shapes)
                if (s.interior || s.exterior) return true;
        return false;
    }
};

}  // namespace iris
