#include "render/stokes_output.h"

#include "core/error.h"
#include "render/render_output.h"

namespace iris {

Image stokesImage(const StokesFilm& film, const ColorManager& colors, const std::string& outputSpace,
                  const std::vector<std::string>& names) {
    Image out(film.width(), film.height(), 12);
    out.channelNames.clear();
    for (int k = 0; k < 4; ++k) {
        const Image c = filmImage(film.component(k), false, colors, outputSpace);
        for (size_t p = 0; p < c.pixelCount(); ++p)
            for (int j = 0; j < 3; ++j) out.pixels[12 * p + 3 * size_t(k) + size_t(j)] = c.pixels[3 * p + size_t(j)];
        for (int j = 0; j < 3; ++j) out.channelNames.push_back(strCat("S", k, ".", names[size_t(j)]));
    }
    return out;
}

Image appendChannels(const Image& image, const Image& extra) {
    const int a = image.channels, b = extra.channels;
    Image out(image.width, image.height, a + b);
    out.channelNames = image.channelNames.empty() ? std::vector<std::string>{"R", "G", "B"} : image.channelNames;
    out.channelNames.insert(out.channelNames.end(), extra.channelNames.begin(), extra.channelNames.end());
    for (size_t p = 0; p < image.pixelCount(); ++p) {
        for (int c = 0; c < a; ++c) out.pixels[size_t(a + b) * p + size_t(c)] = image.pixels[size_t(a) * p + size_t(c)];
        for (int c = 0; c < b; ++c) out.pixels[size_t(a + b) * p + size_t(a + c)] = extra.pixels[size_t(b) * p + size_t(c)];
    }
    return out;
}

}  // namespace iris
