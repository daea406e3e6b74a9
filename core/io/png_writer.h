// A small PNG encoder (W3C "Portable Network Graphics (PNG) Specification", 2nd ed., ISO/IEC
// 15948:2003) for the 8-bit image `render` writes beside every EXR: writing it through the
// OpenImageIO module meant loading ~250 shared libraries (≈ 0.3 s of CPU per render, issue 17);
// this writer needs only zlib. Non-interlaced, 8 bits per sample, per-row adaptive filter.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace iris {

/// The PNG file of a width×height image with `channels` 8-bit samples per pixel (1 grey, 2 grey +
/// alpha, 3 RGB, 4 RGBA), rows top first. Throws iris::Error for other channel counts or sizes.
std::vector<uint8_t> encodePNG(int width, int height, int channels, const uint8_t* pixels);

}  // namespace iris
