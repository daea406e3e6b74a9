// Mitsuba's binary grid-volume format `.vol` (Mitsuba 0.6 src/volume/gridvolume.cpp; Mitsuba 3
// src/render/volumegrid.cpp, VolumeGrid::read, and the format table of src/volumes/grid.cpp).
// Little endian throughout:
//   bytes 0-2   'V' 'O' 'L'
//   byte  3     version, 3
//   int32       encoding: 1 = float32, 2 = float16, 3 = uint8, 4 = quantized directions
//               (Mitsuba 0.6's EVolumeType; Mitsuba 3 reads only 1). Supported here: 1 and 3
//               (uint8 v is read as v/255, as Mitsuba 0.6 does); 2 and 4 are refused.
//   int32 ×3    xres, yres, zres
//   int32       channels
//   float32 ×6  bounding box xmin ymin zmin xmax ymax zmax (Mitsuba 3 ignores it unless the
//               gridvolume asks for use_grid_bbox)
//   data        value (x, y, z, c) at index ((z·yres + y)·xres + x)·channels + c
// Every size in the header is checked against the file length before anything is allocated, and
// the held floats are charged to the memory budget (core/memory_budget.h) first.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "core/math.h"

namespace iris {

struct VolumeGridData {
    int xres = 0, yres = 0, zres = 0, channels = 0;
    vec3 bboxMin{0.0f}, bboxMax{0.0f};  // as written in the file
    std::vector<float> values;          // ((z·yres + y)·xres + x)·channels + c

    size_t index(int x, int y, int z, int c) const {
        return ((size_t(z) * size_t(yres) + size_t(y)) * size_t(xres) + size_t(x)) * size_t(channels) + size_t(c);
    }
    float at(int x, int y, int z, int c) const { return values[index(x, y, z, c)]; }
};

/// Largest channel count accepted (Mitsuba 3's gridvolume uses 1, 3 or 6).
constexpr int kMaxVolChannels = 64;

/// Read a .vol file. Throws iris::Error "path: ..." naming what is wrong (cannot open, bad magic
/// or version, unsupported encoding, bad resolution or channel count, size mismatch or truncated
/// data, non-finite values, over the memory limit).
VolumeGridData readVolFile(const std::string& path);

/// The same, from the file's bytes already in memory (`name` is used in messages).
VolumeGridData parseVol(const std::string& bytes, const std::string& name);

}  // namespace iris
