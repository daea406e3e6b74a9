// The signed-distance-grid shape (Mitsuba 3 `sdfgrid`, src/shapes/sdfgrid.cpp; core/sdf_grid.h):
// `filename`, a 1-channel .vol grid of signed distances (negative inside) sampled over the unit cube
// (sample (i, j, k) at (i, j, k)/(res − 1)); `normals`, the shading normal, "smooth" (default:
// Hansson-Söderlund et al. 2022's blend, continuous across voxels) or "analytic" (the gradient of
// the trilinear interpolant, which is also the geometric normal either way); `to_world`, any
// invertible affine map (Mitsuba 3 warns on rotations, which its voxel boxes do not follow, and
// suggests instancing; iris bounds each voxel by its 8 transformed corners). Each voxel the surface
// passes through is one Embree user primitive, tested exactly (core/sdf_grid_intersection.h).
// As in Mitsuba 3, the shape has no uv (uv = 0, tangents around the normal) and cannot be an area
// emitter (render/loader/shape_loader.cpp refuses one); the .vol file's bounding box is ignored.
#include "core/io/vol_reader.h"
#include "media/volumes/volume.h"  // readToWorld: an invertible, finite to_world
#include "render/shapes/shape.h"

namespace iris {

namespace {

bool readNormals(const Properties& p) {
    const std::string mode = p.getString("normals", "smooth");
    if (mode != "smooth" && mode != "analytic")
        failAt(p.locationOf("normals"), "sdfgrid: normals '", mode, "' is not supported (supported: smooth, analytic)");
    return mode == "smooth";
}

std::shared_ptr<ShapeDescription> createSdfGrid(const Properties& p) {
    auto s = std::make_shared<ShapeDescription>();
    s->type = ShapeDescription::Type::SdfGrid;
    s->name = !p.id().empty() ? p.id() : p.type();
    const bool smooth = readNormals(p);
    const mat4 toWorld = readToWorld(p);
    const std::string file = p.getString("filename");
    s->sdf = withLocation(p.locationOf("filename"), [&] {
        VolumeGridData g = readVolFile(file);
        if (g.channels != 1) fail(file, ": an sdfgrid needs a 1-channel grid, this one has ", g.channels, " channels");
        return std::make_shared<const SdfGrid>(makeSdfGrid(ivec3(g.xres, g.yres, g.zres), std::move(g.values), toWorld, smooth, file));
    });
    return s;
}

}  // namespace

IRIS_REGISTER(ShapeRegistry, "sdfgrid", createSdfGrid);

}  // namespace iris
