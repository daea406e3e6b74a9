#include "render/films/film_description.h"

namespace iris {

namespace {
constexpr int kMaxFilmSide = 1 << 16;
constexpr int64_t kMaxFilmPixels = int64_t(1) << 28;
}  // namespace

void readFilmSize(const Properties& p, FilmDescription& d) {
    d.width = p.getInt("width", 768);
    d.height = p.getInt("height", 576);
    if (d.width < 1 || d.height < 1 || d.width > kMaxFilmSide || d.height > kMaxFilmSide ||
        int64_t(d.width) * d.height > kMaxFilmPixels)
        failAt(p.location(), "film size ", d.width, "x", d.height, " is out of range (1..", kMaxFilmSide,
               " per side, at most 2^28 pixels)");
}

ReconstructionFilterPtr readFilter(const Properties& p) {
    PropertiesPtr filter = p.getObject("rfilter", false);
    for (const PropertiesPtr& c : p.children()) {
        if (c->tag() != "rfilter") failAt(c->location(), "unexpected <", c->tag(), "> inside <film>");
        if (filter) failAt(c->location(), "film has more than one rfilter");
        filter = c;
    }
    if (!filter) return nullptr;
    if (filter->tag() != "rfilter") failAt(p.locationOf("rfilter"), "parameter 'rfilter' must be an <rfilter>");
    return RFilterRegistry::instance().create(*filter);
}

}  // namespace iris
