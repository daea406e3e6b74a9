#include "render/film_output.h"

namespace iris {

const char* filmColorSpace(bool rgbMode) { return rgbMode ? kColorSpaceLinearRec709 : kColorSpaceXYZ; }

Image filmOutputImage(const Film& film, bool rgbMode, const ColorManager& colors, const std::string& outputSpace) {
    Image img(film.width(), film.height(), 3);
    img.pixels = film.meanImage();
    colors.convert(img.pixels.data(), img.pixelCount(), filmColorSpace(rgbMode), outputSpace);
    return img;
}

}  // namespace iris
