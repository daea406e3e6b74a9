#include "render/scene_memory.h"

#include <algorithm>
#include <vector>

#include "core/error.h"

namespace iris {

namespace {

// Peak resident bytes of Embree 3.13.5 (Debian 12) building a scene of high build quality, measured
// over 10^6 and 4·10^6 triangles in one mesh (114 and 94 bytes per triangle besides iris's own
// vertex and index arrays, which the mesh readers charge) and 2·10^5 and 10^6 user geometries of one
// primitive each, as iris makes for every sphere and cylinder (281 and 267 bytes each). Instances
// are counted as user geometries. Rounded up.
constexpr uint64_t kBytesPerTriangle = 128;
constexpr uint64_t kBytesPerGeometry = 320;
// The Scene's own record of each shape (its ShapeData: the description, material and area light).
constexpr uint64_t kBytesPerShapeRecord = 32;

struct Counts {
    uint64_t triangles = 0, geometries = 0, shapes = 0;
};

void count(const ShapeDescription& s, Counts& c) {
    ++c.shapes;
    if (s.type == ShapeDescription::Type::Mesh) c.triangles += s.mesh ? s.mesh->triangleCount() : 0;
    ++c.geometries;
}

Counts countOf(const SceneDescription& desc) {
    Counts c;
    for (const ShapeDescription& s : desc.shapes) count(s, c);
    std::vector<const ShapeGroupDescription*> groups;
    for (const InstanceDescription& inst : desc.instances) {
        ++c.geometries;
        if (std::find(groups.begin(), groups.end(), inst.group.get()) != groups.end()) continue;
        groups.push_back(inst.group.get());
        for (const ShapeDescription& s : inst.group->shapes) count(s, c);
    }
    return c;
}

}  // namespace

uint64_t sceneGeometryBytes(const SceneDescription& desc) {
    const Counts c = countOf(desc);
    return c.triangles * kBytesPerTriangle + c.geometries * kBytesPerGeometry + c.shapes * kBytesPerShapeRecord;
}

std::shared_ptr<const MemoryReservation> chargeSceneGeometry(const SceneDescription& desc) {
    const Counts c = countOf(desc);
    MemoryAccount account;
    chargeMemory(sceneGeometryBytes(desc), strCat(desc.sourceFile, ": the ray-tracing geometry of ", c.shapes, " shapes (", c.triangles,
                                                  " triangles) and ", desc.instances.size(), " instances"));
    return account.take();
}

}  // namespace iris
