// What a finished render becomes on disk: the film's mean converted to an output colour space
// through OpenColorIO, and the metadata every EXR records (mode, N, spp, seed, time, rays, ...).
// One definition shared by the `render` executable and the Python module (apps/python), so an
// image rendered from Python equals the CLI's bit for bit.
#pragma once

#include <string>

#include "core/io/image.h"
#include "render/film.h"
#include "render/renderer.h"
#include "spectral/color_management.h"

namespace iris {

/// The colour space the film's values are in: CIE-XYZ (spectral mode) or lin_rec709 (RGB mode).
const char* filmColorSpace(bool rgbMode);

/// The film's mean image (3 channels) converted from filmColorSpace(rgbMode) to `outputSpace`
/// (also what `merge` writes for added film states, so a merged split render equals the unsplit one).
Image filmImage(const Film& film, bool rgbMode, const ColorManager& colors, const std::string& outputSpace);

/// The EXR header of a render (the "iris.*" keys of docs/rendering.md).
ImageMetadata renderMetadata(const Scene& scene, const std::string& scenePath, const Renderer& renderer,
                             const RenderOptions& opt, const RenderStats& st, const ColorManager& colors,
                             const std::string& outputSpace);

}  // namespace iris
