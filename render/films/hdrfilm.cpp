// Mitsuba's "hdrfilm": a high-dynamic-range image. iris always writes an OpenEXR image (and a PNG
// beside it, see apps/render), so the format parameters are checked and otherwise only accepted.
#include "render/films/film_description.h"

namespace iris {

namespace {

std::shared_ptr<FilmDescription> createHdrFilm(const Properties& p) {
    auto d = std::make_shared<FilmDescription>();
    readFilmSize(p, *d);
    const std::string fmt = p.getString("pixel_format", "rgb");
    if (fmt != "rgb" && fmt != "rgba")
        failAt(p.locationOf("pixel_format"), "pixel_format '", fmt, "' is not supported (supported: rgb, rgba)");
    const std::string comp = p.getString("component_format", "float32");
    if (comp != "float16" && comp != "float32")
        failAt(p.locationOf("component_format"), "component_format '", comp, "' is not supported (supported: float16, float32)");
    p.getString("file_format", "openexr");  // the output format is chosen by the application
    p.getBool("banner", false);
    d->filter = readFilter(p);
    return d;
}

}  // namespace

IRIS_REGISTER(FilmRegistry, "hdrfilm", createHdrFilm);

}  // namespace iris
