// The renderable scene: Embree geometry for ray queries, per-shape shading data, materials and
// lights, built once from a SceneDescription.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "render/lights/light.h"
#include "core/ray.h"
#include "render/scene_description.h"

namespace iris {

class Scene {
public:
    explicit Scene(SceneDescription desc);
    ~Scene();
    Scene(const Scene&) = delete;
    Scene& operator=(const Scene&) = delete;

    /// Closest hit along the ray (direction need not be normalised; t is in units of |d|).
    std::optional<SurfaceInteraction> intersect(const Ray& ray) const;
    /// True if anything blocks the segment [tmin, ray.tMax).
    bool occluded(const Ray& ray) const;
    /// Shadow test between two surface points (both offset off their surfaces).
    bool visible(const SurfaceInteraction& from, const vec3& pLight, const vec3& nLight) const;
    bool visibleInfinite(const SurfaceInteraction& from, const vec3& dir) const;

    const SceneDescription& description() const { return desc_; }
    /// The shape of a SurfaceInteraction's shapeIndex: a top-level shape or a shape of a group
    /// (then shared by all the group's instances).
    const ShapeDescription& shape(int shapeIndex) const;
    const std::vector<LightPtr>& lights() const { return lights_; }
    const std::vector<const Light*>& infiniteLights() const { return infinite_; }
    const SceneBounds& bounds() const { return bounds_; }
    size_t triangleCount() const { return triangles_; }
    /// The Embree scene (RTCScene), for benchmarks that measure bare traversal. Up to
    /// kMaxFlatShapes top-level spheres and cylinders are not in it: Scene tests them itself.
    void* embreeScene() const { return scene_; }
    static constexpr size_t kMaxFlatShapes = 8;

private:
    struct ShapeData;
    struct InstanceData;
    /// A top-level sphere or cylinder tested outside Embree (shapes_[index]).
    struct FlatShape {
        unsigned index;
        bool cylinder;
    };
    void addShapeData(const ShapeDescription& s);
    void addInstances(vec3& lo, vec3& hi);
    void hitInteraction(size_t index, unsigned prim, float b1, float b2, const Ray& ray, float t, SurfaceInteraction& si) const;

    SceneDescription desc_;
    std::vector<ShapeData> shapes_;         // the top-level shapes (index = Embree geometry ID), then each group's
    std::vector<InstanceData> instances_;   // Embree geometry ID firstInstanceID_ + index
    std::vector<FlatShape> flat_;           // the analytic shapes Scene tests itself, in shape order
    bool embreeGeometries_ = false;         // the Embree scene holds any geometry
    std::vector<void*> groupScenes_;        // RTCScene of each shape group
    unsigned firstInstanceID_ = 0;
    std::vector<LightPtr> lights_;          // all lights incl. area lights
    std::vector<const Light*> infinite_;
    SceneBounds bounds_;
    size_t triangles_ = 0;
    void* device_ = nullptr;  // RTCDevice
    void* scene_ = nullptr;   // RTCScene
    MaterialPtr defaultMaterial_;
    std::shared_ptr<const MemoryReservation> geometryMemory_;  // the Embree estimate charged to the budget
};

}  // namespace iris
