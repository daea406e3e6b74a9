// Everything a scene file describes, as plain data: the scene loader fills it, Scene::build()
// turns it into Embree geometry, lights and a camera. Units: scene units for lengths; radiance
// in the relative units of docs/conventions.md.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/math.h"
#include "core/mesh.h"
#include "materials/material.h"
#include "spectral/spectrum.h"

namespace iris {

class Light;

struct ShapeDescription {
    enum class Type { Mesh, Sphere } type = Type::Mesh;
    std::shared_ptr<TriangleMesh> mesh;  // Mesh: already in world space
    vec3 center{0.0f};                   // Sphere (world space)
    float radius = 1.0f;
    bool flipNormals = false;            // Sphere: normals point inwards
    bool faceNormals = false;            // Mesh: ignore vertex normals
    MaterialPtr material;                // nullptr: the default diffuse (0.5) material
    SpectrumPtr emission;                // area emitter radiance (Illuminant kind), or nullptr
    std::string name;                    // for messages
};

struct CameraDescription {
    mat4 toWorld{1.0f};  // camera looks along +z of its frame, up is +y (Mitsuba convention)
    float fovDegrees = 45.0f;
    enum class FovAxis { X, Y, Diagonal, Smaller, Larger } fovAxis = FovAxis::X;
    int width = 512, height = 512;
    enum class Filter { Box, Gaussian } filter = Filter::Gaussian;
    float filterRadius = 0.5f;        // box: half-width in pixels; gaussian: see film/filter.h
    float gaussianStddev = 0.5f;      // pixels (Mitsuba's default)
};

struct IntegratorDescription {
    std::string type = "path";  // "path" or "direct"
    int maxDepth = -1;          // -1: unlimited (Russian roulette terminates)
    int rrDepth = 5;            // Russian roulette starts after this many bounces
    bool hideEmitters = false;
};

struct SceneDescription {
    std::string sourceFile;  // for messages and metadata
    std::vector<ShapeDescription> shapes;
    std::vector<std::shared_ptr<Light>> lights;  // non-area lights (point, spot, env, ...)
    CameraDescription camera;
    IntegratorDescription integrator;
    int spp = 16;  // sampler sample_count
};

}  // namespace iris
