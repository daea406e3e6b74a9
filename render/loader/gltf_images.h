// glTF images (glTF 2.0 §3.8.2: PNG or JPEG, from a URI, a data URI or a buffer view) decoded by
// core's image reader (OpenImageIO module, with its hardening), as linear float bitmaps.
#pragma once

#include <memory>

#include "materials/textures/bitmap.h"
#include "render/loader/gltf_document.h"

namespace iris::gltf {

/// Image `index`, its RGB decoded from sRGB when `srgb` (colour textures, §3.9.6; alpha stays
/// linear), else as stored. Errors name the file and `path`.
std::shared_ptr<const Bitmap> decodeImage(const Document& doc, int index, bool srgb, const std::string& path);

}  // namespace iris::gltf
