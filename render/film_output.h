// The image a film becomes on disk: the per-pixel means in the film's colour space (CIE XYZ in
// spectral mode, linear Rec.709 in RGB mode) converted through OpenColorIO to the output space.
// One function for `render` and for `merge` of film states, so that a merged split render is
// written exactly as the unsplit render.
#pragma once

#include <string>

#include "core/io/image.h"
#include "render/film.h"
#include "spectral/color_management.h"

namespace iris {

/// The colour space of the film's values.
const char* filmColorSpace(bool rgbMode);
/// Mean image converted to `outputSpace`.
Image filmOutputImage(const Film& film, bool rgbMode, const ColorManager& colors, const std::string& outputSpace);

}  // namespace iris
