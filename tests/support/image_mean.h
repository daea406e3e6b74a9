// Renders of small scenes given as XML, and the statistic the analytic render tests compare: the
// mean of one channel over all pixels with its standard error estimated from the spread of the
// (independent, identically distributed) pixel means.
#pragma once

#include <algorithm>
#include <cmath>
#include <string>

#include "render/film.h"
#include "render/loader/scene_loader.h"
#include "render/renderer.h"
#include "render/scene.h"

namespace iris::test {

struct ImageMean {
    double mean = 0, stderr_ = 0;
};

/// Mean of channel c (0, 1, 2) over all pixels and its standard error.
inline ImageMean imageMean(const Film& f, int c) {
    double s = 0, s2 = 0;
    const int n = f.width() * f.height();
    for (int y = 0; y < f.height(); ++y)
        for (int x = 0; x < f.width(); ++x) {
            const double v = f.pixel(x, y)[c];
            s += v;
            s2 += v * v;
        }
    ImageMean m;
    m.mean = s / n;
    m.stderr_ = std::sqrt(std::max(0.0, s2 / n - m.mean * m.mean) / (n - 1));
    return m;
}

/// The scene `xml` (relative paths from ".") rendered on 2 threads into a width × height film.
inline Film renderXml(const std::string& xml, int width, int height, int spp, uint64_t seed, bool rgb) {
    const Scene s(loadSceneFromString(xml, "."));
    RenderOptions opt;
    opt.spp = spp;
    opt.seed = seed;
    opt.rgbMode = rgb;
    opt.threads = 2;
    Film film(width, height);
    Renderer(s, opt).render(film);
    return film;
}

}  // namespace iris::test
