// The memory of a scene's ray-tracing structures, charged to the memory budget (core/memory_budget.h)
// before Embree builds them (issue 38 item 5: 10^6 spheres were not bounded by --memory-limit).
#pragma once

#include <cstdint>
#include <memory>

#include "core/memory_budget.h"
#include "render/scene_description.h"

namespace iris {

/// Estimated bytes of the Embree geometries and BVHs of `desc` (top-level shapes, each shape group
/// once, each instance) and of the Scene's per-shape data.
uint64_t sceneGeometryBytes(const SceneDescription& desc);

/// Charge sceneGeometryBytes(desc) ("scene.xml: Embree geometry of N shapes ..." over the limit
/// throws iris::Error) and return the reservation, held for as long as the Scene lives.
std::shared_ptr<const MemoryReservation> chargeSceneGeometry(const SceneDescription& desc);

}  // namespace iris
