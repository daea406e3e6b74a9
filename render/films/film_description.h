// Films (Mitsuba's <film>): the image size, its reconstruction filter and how it is written.
// Every film type registers a factory in FilmRegistry; the film's nested <rfilter> is created
// through RFilterRegistry (render/filters/).
#pragma once

#include <optional>

#include "core/registry.h"
#include "render/films/ldr_tonemap.h"
#include "render/filters/rfilter.h"

namespace iris {

struct FilmDescription {
    int width = 768, height = 576;  // Mitsuba's defaults
    ReconstructionFilterPtr filter;  // nullptr: Mitsuba's default, a gaussian of stddev 0.5 px
    std::optional<LdrSettings> ldr;  // ldrfilm: how the PNG is made (else OpenColorIO's display view)
};

using FilmRegistry = Registry<FilmDescription>;

/// The film's width and height (Mitsuba's defaults 768 × 576), range-checked.
void readFilmSize(const Properties& film, FilmDescription& d);
/// The film's one <rfilter> (named or nested), or nullptr.
ReconstructionFilterPtr readFilter(const Properties& film);

}  // namespace iris
