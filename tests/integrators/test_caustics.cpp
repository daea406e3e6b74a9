// The caustic scene of issue 35 (scenes/caustics/glass_sphere.xml, quick form; the converged
// comparison is experiments/caustics.py): a glass sphere above a diffuse floor. With a point light,
// `path` cannot render the caustic (shadow rays stop at the glass, no BSDF sample hits a point);
// `ptracer` and `bdpt` render it, and agree with each other on the floor. With a small area light
// of the same power, all three agree. The same for the sphere coated with a thin film.
#include <gtest/gtest.h>

#include <cstdio>

#include "core/source_tree.h"
#include "render/loader/scene_loader.h"
#include "render/renderer.h"
#include "render/scene.h"
#include "tests/support/agreement.h"

using namespace iris;
using namespace iris::test;

namespace {

constexpr int kRes = 16;

Film renderCaustic(const std::string& integrator, const std::string& light, const std::string& coating, int spp, uint64_t seed) {
    const std::string path = sourcePath("scenes/caustics/glass_sphere.xml");
    const Scene scene(loadScene(path, {{"integrator", integrator}, {"light", light}, {"coating", coating},
                                       {"res", std::to_string(kRes)}, {"max_depth", "6"}}));
    RenderOptions opt;
    opt.spp = spp;
    opt.seed = seed;
    opt.threads = 2;
    Film film(kRes, kRes);
    Renderer(scene, opt).render(film);
    return film;
}

/// The floor in front of and below the sphere (the lower half of the image), where the caustic is.
const PixelRect kFloor{0, kRes / 2, kRes, kRes};

double meanY(const Film& f, const PixelRect& r) {
    double s = 0;
    for (int y = r.y0; y < r.y1; ++y)
        for (int x = r.x0; x < r.x1; ++x) s += f.pixel(x, y).y;
    return s / ((r.x1 - r.x0) * (r.y1 - r.y0));
}

/// The brightest 2×2 block of the floor in `f` (the caustic's centre) and its mean luminance.
std::pair<PixelRect, double> brightestBlock(const Film& f) {
    std::pair<PixelRect, double> best{{0, 0, 0, 0}, -1.0};
    for (int y = kFloor.y0; y + 2 <= kFloor.y1; ++y)
        for (int x = 0; x + 2 <= kRes; ++x) {
            const PixelRect r{x, y, x + 2, y + 2};
            const double m = meanY(f, r);
            if (m > best.second) best = {r, m};
        }
    return best;
}

TEST(Caustics, APointLightsCausticIsMissedByPathAndFoundByLightTracing) {
    for (const char* coating : {"glass", "thinfilm"}) {
        const Film bdpt = renderCaustic("bdpt", "point", coating, 128, 1);
        const Film ptracer = renderCaustic("ptracer", "point", coating, 512, 2);
        const Film path = renderCaustic("path", "point", coating, 128, 3);
        const auto [caustic, bdptY] = brightestBlock(bdpt);
        const double pathY = meanY(path, caustic), ptracerY = meanY(ptracer, caustic);
        std::printf("[ caustics ] %s, point light, caustic block (%d, %d): bdpt %.4f ptracer %.4f path %.4f\n", coating, caustic.x0,
                    caustic.y0, bdptY, ptracerY, pathY);
        EXPECT_LT(pathY, 0.25 * bdptY) << coating;  // path sees the shadow only
        const Agreement a = compareFilms(ptracer, bdpt, kFloor);
        EXPECT_TRUE(a.passed()) << coating << " ptracer vs bdpt on the floor: |z| " << a.maxAbsZ << " at " << a.where;
    }
}

TEST(Caustics, AnAreaLightsCausticIsFoundByAllThree) {
    // `path` finds this caustic only by BSDF samples that hit the small light: rare, large values
    // whose variance a few hundred samples underestimate; blocks of 8×8 pixels average them.
    const Film bdpt = renderCaustic("bdpt", "area", "glass", 512, 1);
    const Film path = renderCaustic("path", "area", "glass", 4096, 2);
    const Film ptracer = renderCaustic("ptracer", "area", "glass", 1024, 3);
    const Agreement a = compareFilms(bdpt, path, 8);
    EXPECT_TRUE(a.passed()) << "bdpt vs path: |z| " << a.maxAbsZ << " at " << a.where;
    const Agreement b = compareFilms(ptracer, path, kFloor, 8);
    EXPECT_TRUE(b.passed()) << "ptracer vs path on the floor: |z| " << b.maxAbsZ << " at " << b.where;
    std::printf("[ caustics ] area light: bdpt vs path |z| %.2f, ptracer vs path (floor) |z| %.2f (thresholds %.2f, %.2f)\n", a.maxAbsZ,
                b.maxAbsZ, a.threshold, b.threshold);
}

}  // namespace
