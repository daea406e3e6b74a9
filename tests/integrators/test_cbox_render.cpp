// The Cornell box scenes of ../shared render as the box they describe: red wall on the left,
// green on the right, lit from the ceiling, in RGB and in measured-spectrum form.
#include <gtest/gtest.h>

#include <filesystem>

#include "core/source_tree.h"
#include "render/film.h"
#include "render/loader/scene_loader.h"
#include "render/renderer.h"
#include "render/scene.h"
#include "spectral/color_management.h"

using namespace iris;

namespace {

std::string cboxPath(const char* name) { return sourcePath(std::string("../shared/data/scenes/cbox/") + name); }

/// Mean linear Rec.709 colour over a rectangle of the image (fractions of width/height).
vec3 regionMean(const std::vector<float>& rgb, int w, int h, float x0, float x1, float y0, float y1) {
    vec3 s(0.0f);
    int n = 0;
    for (int y = int(y0 * h); y < int(y1 * h); ++y)
        for (int x = int(x0 * w); x < int(x1 * w); ++x, ++n)
            for (int c = 0; c < 3; ++c) s[c] += rgb[3 * (size_t(y) * w + x) + c];
    return s / float(n);
}

}  // namespace

TEST(CornellBox, RendersRedLeftGreenRightInBothForms) {
    for (const char* file : {"cbox-rgb.xml", "cbox-spectral.xml"}) {
        if (!std::filesystem::exists(cboxPath(file))) GTEST_SKIP() << "../shared is not beside the repository";
        const Scene scene(loadScene(cboxPath(file), {{"res", "32"}, {"spp", "32"}}));
        for (const bool rgbMode : {true, false}) {
            RenderOptions opt;
            opt.rgbMode = rgbMode;
            opt.seed = 4;
            Film film(32, 32);
            Renderer(scene, opt).render(film);
            std::vector<float> px = film.meanImage();
            if (!rgbMode) ColorManager().convert(px.data(), px.size() / 3, kColorSpaceXYZ, kColorSpaceLinearRec709);
            const vec3 left = regionMean(px, 32, 32, 0.06f, 0.16f, 0.3f, 0.6f);
            const vec3 right = regionMean(px, 32, 32, 0.84f, 0.94f, 0.3f, 0.6f);
            // Brightest pixel near the top centre: the emitter.
            vec3 light(0.0f);
            for (int y = 3; y < 10; ++y)
                for (int x = 11; x < 21; ++x)
                    if (px[3 * (y * 32 + x) + 1] > light.y) light = vec3(px[3 * (y * 32 + x)], px[3 * (y * 32 + x) + 1], px[3 * (y * 32 + x) + 2]);
            SCOPED_TRACE(std::string(file) + (rgbMode ? " rgb mode" : " spectral mode"));
            std::printf("%s %s: left %.3f %.3f %.3f right %.3f %.3f %.3f light %.3f %.3f %.3f\n", file, rgbMode ? "rgb" : "spectral",
                        left.x, left.y, left.z, right.x, right.y, right.z, light.x, light.y, light.z);
            EXPECT_GT(left.x, 3.0f * left.y);  // red wall
            // The light is warm, so the green wall is judged against the red one: its G/R ratio is
            // far higher.
            EXPECT_GT(right.y / right.x, 4.0f * left.y / left.x);
            EXPECT_GT(light.y, 3.0f * std::max(left.y, right.y));  // the emitter is the brightest
        }
    }
}
