// The Stokes film as image channels (docs/polarization.md): S0..S3, each converted from CIE XYZ to
// the output colour space like the image (a linear map, so the signed S1..S3 convert as well),
// named S<k>.<channel> after the image's channels (Mitsuba 3 stokes.cpp: S0.R, S0.G, ..., S3.B).
// Shared by `render` and the Python module.
#pragma once

#include <string>

#include "core/io/image.h"
#include "render/stokes_film.h"
#include "spectral/color_management.h"

namespace iris {

/// 12 channels S0.R, S0.G, S0.B, S1.R, ..., S3.B (R, G, B replaced by `names` if given).
Image stokesImage(const StokesFilm& film, const ColorManager& colors, const std::string& outputSpace,
                  const std::vector<std::string>& names = {"R", "G", "B"});

/// `image` (3 channels) followed by the channels of `extra`.
Image appendChannels(const Image& image, const Image& extra);

}  // namespace iris
