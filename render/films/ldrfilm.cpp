// Mitsuba 0.6's "ldrfilm": an 8-bit image after exposure, tone mapping and gamma. iris writes the
// EXR of the linear film as always and the PNG beside it with these settings (apps/render;
// render/films/ldr_tonemap.h) instead of the OpenColorIO display transform.
#include "render/films/film_description.h"

namespace iris {

namespace {

std::shared_ptr<FilmDescription> createLdrFilm(const Properties& p) {
    auto d = std::make_shared<FilmDescription>();
    readFilmSize(p, *d);
    LdrSettings s;
    s.gamma = p.getFloat("gamma", -1.0f);
    if (!(s.gamma == -1.0f || s.gamma > 0)) failAt(p.locationOf("gamma"), "ldrfilm gamma must be -1 (sRGB) or positive");
    s.exposure = p.getFloat("exposure", 0.0f);
    const std::string method = p.getString("tonemap_method", "gamma");
    if (method == "reinhard") s.method = LdrSettings::Method::Reinhard;
    else if (method != "gamma")
        failAt(p.locationOf("tonemap_method"), "tonemap_method '", method, "' is not one of gamma, reinhard");
    s.key = p.getFloat("reinhard_key", 0.18f);
    s.burn = p.getFloat("reinhard_burn", 0.0f);
    if (!(s.key > 0) || !(s.burn >= 0 && s.burn <= 1))
        failAt(p.location(), "ldrfilm: reinhard_key must be > 0 and reinhard_burn in [0, 1]");
    // Accepted: the file format and pixel layout of the PNG are iris's; the banner is never drawn.
    p.getString("file_format", "png");
    p.getString("pixel_format", "rgb");
    p.getBool("banner", true);
    p.getBool("high_quality_edges", false);
    d->ldr = s;
    d->filter = readFilter(p);
    return d;
}

}  // namespace

IRIS_REGISTER(FilmRegistry, "ldrfilm", createLdrFilm);

}  // namespace iris
