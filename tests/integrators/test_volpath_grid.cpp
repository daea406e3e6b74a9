// Heterogeneous (grid) media through the volumetric integrators: delta tracking with null
// collisions against the majorant grid and ratio-tracked shadow rays. A grid of known
// density along the view axis gives the Beer–Lambert transmittance e^{−∫σ_t}; a non-absorbing
// grid medium in a uniform environment keeps radiance 1 (furnace), in RGB and spectral mode.
// Fixed seeds; tolerances of 5 standard errors of the image mean (spread of the pixel means).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "tests/support/image_mean.h"
#include "tests/support/vol_file.h"

using namespace iris;

namespace {

constexpr int kRes = 8;

/// The camera at z = 4 looking at the origin (fov degrees) under a constant environment of
/// radiance 1, the integrator, and a cube [−1, 1]³ with a null boundary enclosing a heterogeneous
/// medium whose sigma_t grid (`file`, filter `filter`) fills the cube, with albedo `albedo`.
std::string scene(const std::string& integ, const std::string& file, const std::string& filter, float albedo, float fov) {
    char buf[2400];
    std::snprintf(buf, sizeof buf, R"(<scene version="3.0.0">
  <integrator type="%s"/>
  <sensor type="perspective"><float name="fov" value="%g"/>
    <transform name="to_world"><lookat origin="0 0 4" target="0 0 0" up="0 1 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="%d"/><integer name="height" value="%d"/>
      <rfilter type="box"/></film></sensor>
  <emitter type="constant"><float name="radiance" value="1"/></emitter>
  <medium type="heterogeneous" id="m"><float name="albedo" value="%g"/>
    <volume name="sigma_t" type="gridvolume"><string name="filename" value="%s"/>
      <string name="filter_type" value="%s"/>
      <transform name="to_world"><scale value="2"/><translate value="-1 -1 -1"/></transform></volume></medium>
  <shape type="cube"><bsdf type="null"/><ref name="interior" id="m"/></shape>
</scene>)",
                  integ.c_str(), fov, kRes, kRes, albedo, file.c_str(), filter.c_str());
    return buf;
}

Film render(const std::string& xml, bool rgb, int spp, uint64_t seed = 5) { return test::renderXml(xml, kRes, kRes, spp, seed, rgb); }

using Mean = test::ImageMean;
using test::imageMean;

}  // namespace

TEST(VolPathGrid, BeerLambertThroughALayeredGrid) {
    // Four layers along z of densities 0, 1, 2, 3 (nearest filter), each 0.5 thick in the scaled
    // cube: ∫σ_t = 3 along the axis, so the pixel is e^{−3}; the majorant grid's cells pad into
    // the neighbouring layers, so null collisions occur. A wrong answer (the density times two)
    // is far outside the tolerance.
    const std::string vol = test::writeVolFile("iris_volpath_grid", "layers.vol", ivec3(1, 1, 4), 1, {0, 1, 2, 3});
    for (const char* integ : {"volpath", "volpathmis"}) {
        const Film f = render(scene(integ, vol, "nearest", 0.0f, 0.5f), true, 512);
        const Mean m = imageMean(f, 1);
        EXPECT_NEAR(m.mean, std::exp(-3.0), 5 * m.stderr_ + 1e-3) << integ;
        EXPECT_GT(std::abs(m.mean - std::exp(-6.0)), 10 * m.stderr_) << integ;
    }
}

TEST(VolPathGrid, FurnaceWithARandomGridInBothModes) {
    std::vector<float> v(6 * 5 * 7);
    uint32_t state = 12345;
    for (float& x : v) {
        state = state * 1664525u + 1013904223u;  // a fixed pseudo-random field in [0, 4)
        x = 4.0f * float(state >> 8) * 0x1p-24f;
    }
    const std::string vol = test::writeVolFile("iris_volpath_grid", "random.vol", ivec3(6, 5, 7), 1, v);
    for (const bool rgb : {true, false}) {
        // The environment alone (D65 with Y = 1 in spectral mode) is the reference.
        const std::string empty = R"(<scene version="3.0.0"><integrator type="volpath"/>
  <sensor type="perspective"><float name="fov" value="40"/>
    <transform name="to_world"><lookat origin="0 0 4" target="0 0 0" up="0 1 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/><rfilter type="box"/></film></sensor>
  <emitter type="constant"><float name="radiance" value="1"/></emitter></scene>)";
        const Film e = render(empty, rgb, 64);
        for (const char* integ : {"volpath", "volpathmis"}) {
            const Film f = render(scene(integ, vol, "trilinear", 1.0f, 40.0f), rgb, 128);
            for (int c = 0; c < 3; ++c) {
                const Mean m = imageMean(f, c), r = imageMean(e, c);
                EXPECT_NEAR(m.mean, r.mean, 5 * std::hypot(m.stderr_, r.stderr_) + 2e-3)
                    << integ << (rgb ? " rgb" : " spectral") << " channel " << c;
            }
        }
    }
}
