// Mitsuba's built-in mesh shapes in their canonical frames (core/mesh.h): rectangle [-1,1]² at
// z = 0 facing +z, cube [-1,1]³, unit disk at z = 0 facing +z; placed by to_world.
#include "render/shapes/shape.h"

namespace iris {

namespace {
std::shared_ptr<ShapeDescription> createRectangle(const Properties& p) { return meshShape(p, makeRectangle()); }
std::shared_ptr<ShapeDescription> createCube(const Properties& p) { return meshShape(p, makeCube()); }
std::shared_ptr<ShapeDescription> createDisk(const Properties& p) { return meshShape(p, makeDisk()); }
}  // namespace

IRIS_REGISTER(ShapeRegistry, "rectangle", createRectangle);
IRIS_REGISTER(ShapeRegistry, "cube", createCube);
IRIS_REGISTER(ShapeRegistry, "disk", createDisk);

}  // namespace iris
