// OpenVDB `.vdb` grids (Museth 2013, "VDB: High-resolution sparse volumes with dynamic topology",
// ACM TOG 32(3); read with Debian's libopenvdb) densified into the voxel grid of a Mitsuba `.vol`
// (core/io/vol_reader.h), for `gridvolume` (media/volumes/gridvolume.cpp). Mitsuba 3 reads only
// .vol files; this is iris's form (docs/media.md):
//  - the grid is the one named `gridName`, or the file's only grid when the name is empty;
//  - its voxels are those of the bounding box of its active voxels (index space, inclusive),
//    inactive ones inside the box taking the grid's background value; voxel (i, j, k) of the dense
//    grid is the VDB voxel min + (i, j, k), so the dense grid's cell-centred samples sit where
//    VDB's do (voxel centres at integer index coordinates);
//  - float and double grids give 1 channel, vec3s and vec3d grids 3; other types are refused;
//  - the bounding box is the world-space box of the index box [min − ½, max + ½] under the grid's
//    transform (the 8 corners' bounds), which `use_grid_bbox` maps onto the unit cube.
// The dense floats are charged to the memory budget (core/memory_budget.h) before they are
// allocated, and the file's size is checked against it before OpenVDB reads it.
// OpenVDB itself is linked only into a module loaded on the first read (core/io/vdb_module.h,
// core/io/vdb_loader.h): this file reads the grid's shape through it, charges the budget,
// allocates, then has the module fill the floats.
#pragma once

#include <string>

#include "core/io/vol_reader.h"

namespace iris {

/// Throws iris::Error "path: ..." naming what is wrong (cannot read, no such grid and the grids
/// there are, several grids and no name, unsupported value type, no active voxels, non-finite
/// values, over the memory limit with the bytes it would need, the OpenVDB module not loadable).
VolumeGridData readVdbFile(const std::string& path, const std::string& gridName);

/// True for a file name ending in ".vdb" (any case).
bool isVdbFileName(const std::string& path);

}  // namespace iris
