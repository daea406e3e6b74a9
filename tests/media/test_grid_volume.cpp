// The gridvolume and constvolume plugins (media/volumes/): trilinear and nearest lookups at
// known points against hand-computed values (Mitsuba 3's cell-centred samples), the wrap modes,
// to_world and use_grid_bbox, RGB grids in RGB and spectral mode, the conservative maxValueIn, and
// errors that name the scene line.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>

#include "core/rng.h"
#include "media/volumes/volume.h"
#include "spectral/color_space.h"
#include "spectral/rgb_spectrum_grid.h"
#include "tests/support/error_of.h"
#include "tests/support/vol_file.h"

namespace iris {
namespace {

using test::errorOf;

const SourceLocation kLoc{"scene.xml", 5};

/// A float32 .vol file of the given resolution and values.
std::string writeVol(const std::string& name, ivec3 res, int channels, const std::vector<float>& v,
                     vec3 bmin = vec3(0), vec3 bmax = vec3(1)) {
    return test::writeVolFile("iris_grid_volume_test", name, res, channels, v, bmin, bmax);
}

using Param = std::pair<std::string, PropertyValue>;
std::shared_ptr<Properties> volumeProps(const std::string& type, std::initializer_list<Param> params) {
    auto p = std::make_shared<Properties>("volume", type, kLoc);
    int line = 6;
    for (const auto& [name, value] : params) p->set(name, value, SourceLocation{"scene.xml", line++});
    return p;
}

VolumePtr makeVolume(const std::string& type, std::initializer_list<Param> params,
                     SpectrumKind kind = SpectrumKind::Unbounded) {
    return VolumeRegistry::instance().create(*volumeProps(type, params), kind);
}

const SampledWavelengths kRGB = SampledWavelengths::rgb(defaultChannelWavelengths());

float at(const Volume& v, vec3 p) { return v.eval(p, kRGB)[0]; }
/// The spectral value at one wavelength (nm).
float at(const Volume& v, vec3 p, float lambda) { return v.eval(p, SampledWavelengths::fixed(&lambda, 1))[0]; }

/// 2×2×2 grid with v(x, y, z) = x + 2y + 4z.
std::string linearGrid() {
    std::vector<float> v;
    for (int z = 0; z < 2; ++z)
        for (int y = 0; y < 2; ++y)
            for (int x = 0; x < 2; ++x) v.push_back(float(x + 2 * y + 4 * z));
    return writeVol("linear.vol", ivec3(2), 1, v);
}

/// 4×1×1 grid 0, 1, 2, 3.
std::string rampGrid() { return writeVol("ramp.vol", ivec3(4, 1, 1), 1, {0, 1, 2, 3}); }

TEST(GridVolume, TrilinearSamplesAtCellCentres) {
    const VolumePtr v = makeVolume("gridvolume", {{"filename", linearGrid()}});
    // Voxel (i, j, k) sits at ((i+½)/2, (j+½)/2, (k+½)/2).
    EXPECT_FLOAT_EQ(at(*v, vec3(0.25f)), 0.0f);
    EXPECT_FLOAT_EQ(at(*v, vec3(0.75f, 0.25f, 0.25f)), 1.0f);
    EXPECT_FLOAT_EQ(at(*v, vec3(0.25f, 0.75f, 0.75f)), 6.0f);
    EXPECT_FLOAT_EQ(at(*v, vec3(0.5f)), 3.5f);  // the mean of the 8 voxels
    // x·2 − ½ = 0.25: a quarter of the way from voxel 0 to voxel 1; y likewise: 0.25 + 2·0.25.
    EXPECT_NEAR(at(*v, vec3(0.375f, 0.375f, 0.25f)), 0.75f, 1e-6f);
    // Clamp (the default) beyond the outer centres: the edge voxels' values.
    EXPECT_FLOAT_EQ(at(*v, vec3(0.1f, 0.25f, 0.25f)), 0.0f);
    EXPECT_FLOAT_EQ(at(*v, vec3(1.7f, 0.25f, -3.0f)), 1.0f);
    EXPECT_EQ(v->resolution(), ivec3(2));
    EXPECT_FLOAT_EQ(v->maxValue(), 7.0f);
    EXPECT_FLOAT_EQ(v->range().min, 0.0f);
}

TEST(GridVolume, NearestTakesTheVoxelContainingThePoint) {
    const VolumePtr v = makeVolume("gridvolume", {{"filename", linearGrid()}, {"filter_type", std::string("nearest")}});
    EXPECT_FLOAT_EQ(at(*v, vec3(0.49f, 0.1f, 0.1f)), 0.0f);
    EXPECT_FLOAT_EQ(at(*v, vec3(0.51f, 0.1f, 0.1f)), 1.0f);
    EXPECT_FLOAT_EQ(at(*v, vec3(0.51f, 0.9f, 0.6f)), 7.0f);
}

TEST(GridVolume, WrapModes) {
    const std::string f = rampGrid();
    auto vol = [&](const char* wrap, const char* filter = "trilinear") {
        return makeVolume("gridvolume", {{"filename", f}, {"wrap_mode", std::string(wrap)}, {"filter_type", std::string(filter)}});
    };
    const VolumePtr clamp = vol("clamp"), repeat = vol("repeat"), mirror = vol("mirror");
    const vec3 yz(0.5f);
    auto x = [&](float u) { return vec3(u, yz.y, yz.z); };
    // u = 1: x·4 − ½ = 3.5, between voxel 3 and voxel "4".
    EXPECT_FLOAT_EQ(at(*clamp, x(1.0f)), 3.0f);
    EXPECT_FLOAT_EQ(at(*repeat, x(1.0f)), 1.5f);   // 4 → 0
    EXPECT_FLOAT_EQ(at(*mirror, x(1.0f)), 3.0f);   // 4 → 3
    // u = 1.25: 4.5, between "4" and "5".
    EXPECT_FLOAT_EQ(at(*repeat, x(1.25f)), 0.5f);  // 0 and 1
    EXPECT_FLOAT_EQ(at(*mirror, x(1.25f)), 2.5f);  // 3 and 2
    // u = 0: −0.5, between "−1" and 0.
    EXPECT_FLOAT_EQ(at(*clamp, x(0.0f)), 0.0f);
    EXPECT_FLOAT_EQ(at(*repeat, x(0.0f)), 1.5f);   // −1 → 3
    EXPECT_FLOAT_EQ(at(*mirror, x(0.0f)), 0.0f);   // −1 → 0
    // Whole periods: repeat has period 1, mirror 2.
    EXPECT_FLOAT_EQ(at(*repeat, x(0.375f + 3.0f)), at(*repeat, x(0.375f)));
    EXPECT_FLOAT_EQ(at(*mirror, x(0.375f - 2.0f)), at(*mirror, x(0.375f)));
    EXPECT_FLOAT_EQ(at(*mirror, x(2.0f - 0.375f)), at(*mirror, x(0.375f)));
    // Nearest: u = −0.1 is voxel −1.
    EXPECT_FLOAT_EQ(at(*vol("repeat", "nearest"), x(-0.1f)), 3.0f);
    EXPECT_FLOAT_EQ(at(*vol("mirror", "nearest"), x(-0.1f)), 0.0f);
    EXPECT_FLOAT_EQ(at(*vol("clamp", "nearest"), x(-0.1f)), 0.0f);
}

TEST(GridVolume, ToWorldPlacesTheUnitCube) {
    const mat4 m = glm::scale(glm::translate(mat4(1.0f), vec3(1, 0, 0)), vec3(2));
    const VolumePtr v = makeVolume("gridvolume", {{"filename", linearGrid()}, {"to_world", m}});
    EXPECT_FLOAT_EQ(at(*v, vec3(1 + 2 * 0.75f, 0.5f, 0.5f)), 1.0f);  // local (0.75, 0.25, 0.25)
    EXPECT_FLOAT_EQ(at(*v, vec3(2.0f, 1.0f, 1.0f)), 3.5f);           // local centre
    EXPECT_EQ(v->bounds().lo, vec3(1, 0, 0));
    EXPECT_EQ(v->bounds().hi, vec3(3, 2, 2));
    // A rotation: the world box is that of the rotated cube.
    const mat4 r = glm::rotate(mat4(1.0f), kPiOver4, vec3(0, 0, 1));
    const VolumePtr rv = makeVolume("gridvolume", {{"filename", linearGrid()}, {"to_world", r}});
    EXPECT_NEAR(rv->bounds().lo.x, -std::sqrt(0.5f), 1e-6f);
    EXPECT_NEAR(rv->bounds().hi.y, std::sqrt(2.0f), 1e-6f);
    EXPECT_NEAR(at(*rv, transformPoint(r, vec3(0.75f, 0.25f, 0.25f))), 1.0f, 1e-5f);
}

TEST(GridVolume, UseGridBboxMapsTheFileBox) {
    std::vector<float> v;
    for (int i = 0; i < 8; ++i) v.push_back(float((i & 1) + 2 * ((i >> 1) & 1) + 4 * (i >> 2)));
    const std::string f = writeVol("boxed.vol", ivec3(2), 1, v, vec3(-1), vec3(1));
    const VolumePtr ignored = makeVolume("gridvolume", {{"filename", f}});
    EXPECT_EQ(ignored->bounds().lo, vec3(0));  // Mitsuba 3 ignores the file's box by default
    const VolumePtr used = makeVolume("gridvolume", {{"filename", f}, {"use_grid_bbox", true}});
    EXPECT_EQ(used->bounds().lo, vec3(-1));
    EXPECT_EQ(used->bounds().hi, vec3(1));
    EXPECT_FLOAT_EQ(at(*used, vec3(0.5f, -0.5f, -0.5f)), 1.0f);  // local (0.75, 0.25, 0.25)
}

TEST(GridVolume, RGBGridInRGBMode) {
    const std::string f = writeVol("rgb.vol", ivec3(2, 1, 1), 3, {1, 0, 0.2f, 0, 0.4f, 1});
    const VolumePtr v = makeVolume("gridvolume", {{"filename", f}}, SpectrumKind::Reflectance);
    const SampledSpectrum mid = v->eval(vec3(0.5f), kRGB);
    ASSERT_EQ(mid.size(), 3);
    EXPECT_FLOAT_EQ(mid[0], 0.5f);
    EXPECT_FLOAT_EQ(mid[1], 0.2f);
    EXPECT_FLOAT_EQ(mid[2], 0.6f);
    const SampledSpectrum left = v->eval(vec3(0.25f, 0.5f, 0.5f), kRGB);
    EXPECT_FLOAT_EQ(left[0], 1.0f);
    EXPECT_FLOAT_EQ(left[2], 0.2f);
    EXPECT_FLOAT_EQ(v->range().max, 1.0f);
}

TEST(GridVolume, RGBGridInSpectralModeIsScaledAsMitsuba3) {
    // Grey voxels give flat spectra (spectral/rgb_spectrum_grid.h: greys to 1.7e-4), whatever the
    // parameter's kind: halfway between 0.25 and 0.75, (½S + ½S)(½·0.5 + ½·1.5) = 0.5.
    const std::string f = writeVol("grey.vol", ivec3(2, 1, 1), 3, {0.25f, 0.25f, 0.25f, 0.75f, 0.75f, 0.75f});
    const SampledWavelengths wl = SampledWavelengths::sampleVisible(0.3f, 8);
    for (SpectrumKind kind : {SpectrumKind::Reflectance, SpectrumKind::Unbounded}) {
        const VolumePtr v = makeVolume("gridvolume", {{"filename", f}}, kind);
        const SampledSpectrum s = v->eval(vec3(0.5f), wl);
        ASSERT_EQ(s.size(), 8);
        for (int i = 0; i < 8; ++i) EXPECT_NEAR(s[i], 0.5f, 1e-3f);
        for (int i = 0; i < 8; ++i) EXPECT_LE(s[i], v->maxValue());
    }
    // A coloured voxel is 2m · S(rgb/2m) (Mitsuba 3 grid.cpp), which projects onto its colour but
    // is not the reflectance or unbounded upsampling of the colour itself; blended voxels multiply
    // the blended shapes by the blended scales.
    const vec3 c0(3.0f, 0.5f, 1.0f), c1(0.2f, 0.9f, 0.4f);
    const std::string c = writeVol("col.vol", ivec3(2, 1, 1), 3, {c0.x, c0.y, c0.z, c1.x, c1.y, c1.z});
    const VolumePtr v = makeVolume("gridvolume", {{"filename", c}});
    const RGBSpectrumGrid& grid = RGBSpectrumGrid::instance();
    const vec3 rgb = rgbProjection([&](float lambda) { return at(*v, vec3(0.25f, 0.5f, 0.5f), lambda); }, SpectrumKind::Reflectance);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(rgb[k], c0[k], 2e-3f * 3.0f) << "channel " << k;
    const SampledSpectrum mid = v->eval(vec3(0.5f), wl);
    const SampledSpectrum shape = 0.5f * grid.reflectance(c0 / 6.0f, wl) + 0.5f * grid.reflectance(c1 / 1.8f, wl);
    for (int i = 0; i < 8; ++i) {
        EXPECT_NEAR(mid[i], shape[i] * 0.5f * (6.0f + 1.8f), 1e-5f);
        EXPECT_LE(mid[i], v->maxValue());
    }
    EXPECT_FLOAT_EQ(v->maxValue(), 6.0f);
    // The reflectance upsampling of the same colour (what iris did before) differs in shape.
    const SampledSpectrum old = grid.sample(c0, SpectrumKind::Unbounded, wl);
    const SampledSpectrum now = v->eval(vec3(0.25f, 0.5f, 0.5f), wl);
    float diff = 0.0f;
    for (int i = 0; i < 8; ++i) diff = std::max(diff, std::abs(old[i] - now[i]));
    EXPECT_GT(diff, 0.05f);
}

TEST(GridVolume, MaxValueInBoundsEveryPointOfTheBox) {
    Pcg32 rng(7, 3);
    std::vector<float> vals(5 * 4 * 3);
    for (float& x : vals) x = rng.uniform() * 4.0f;
    const std::string f = writeVol("random.vol", ivec3(5, 4, 3), 1, vals);
    for (const char* wrap : {"clamp", "repeat", "mirror"})
        for (const char* filter : {"trilinear", "nearest"}) {
            const VolumePtr v = makeVolume("gridvolume", {{"filename", f}, {"wrap_mode", std::string(wrap)},
                                                          {"filter_type", std::string(filter)}});
            for (int b = 0; b < 200; ++b) {
                vec3 a(rng.uniform(), rng.uniform(), rng.uniform()), c(rng.uniform(), rng.uniform(), rng.uniform());
                a = a * 3.0f - 1.0f, c = a + c * 0.4f;  // boxes also outside the unit cube
                const float bound = v->maxValueIn(Box3{a, c});
                EXPECT_LE(bound, v->maxValue());
                for (int s = 0; s < 50; ++s) {
                    const vec3 p = a + (c - a) * vec3(rng.uniform(), rng.uniform(), rng.uniform());
                    ASSERT_LE(at(*v, p), bound * (1 + 1e-6f)) << wrap << " " << filter;
                }
            }
        }
}

TEST(GridVolume, ConstVolume) {
    const VolumePtr v = makeVolume("constvolume", {{"value", RGBValue{vec3(0.2f, 0.4f, 0.6f)}}}, SpectrumKind::Reflectance);
    const SampledSpectrum s = v->eval(vec3(10.0f), kRGB);
    EXPECT_FLOAT_EQ(s[0], 0.2f);
    EXPECT_FLOAT_EQ(s[2], 0.6f);
    EXPECT_TRUE(v->isConstant());
    EXPECT_EQ(v->bounds().hi, vec3(1));
    EXPECT_FLOAT_EQ(makeVolume("constvolume", {})->eval(vec3(0), kRGB)[1], 1.0f);  // Mitsuba 3 default 1
    const VolumePtr scaled = makeVolume("constvolume", {{"value", 2.5f}, {"to_world", glm::scale(mat4(1.0f), vec3(3))}});
    EXPECT_FLOAT_EQ(scaled->maxValue(), 2.5f);
    EXPECT_EQ(scaled->bounds().hi, vec3(3));
}

TEST(GridVolume, GetVolumeTakesValuesOrVolumes) {
    Properties p("medium", "heterogeneous", kLoc);
    p.set("a", 0.5f, kLoc);
    p.set("b", volumeProps("gridvolume", {{"filename", rampGrid()}}), kLoc);
    EXPECT_FLOAT_EQ(at(*getVolume(p, "a", SpectrumKind::Unbounded, 1.0f), vec3(0)), 0.5f);
    EXPECT_FLOAT_EQ(at(*getVolume(p, "b", SpectrumKind::Unbounded, 1.0f), vec3(0.375f, 0.5f, 0.5f)), 1.0f);
    EXPECT_FLOAT_EQ(at(*getVolume(p, "c", SpectrumKind::Unbounded, 0.25f), vec3(0)), 0.25f);
    p.set("d", std::make_shared<Properties>("bsdf", "diffuse", kLoc), SourceLocation{"scene.xml", 9});
    EXPECT_NE(errorOf([&] { getVolume(p, "d", SpectrumKind::Unbounded, 1.0f); }).find("scene.xml:9: parameter 'd' must be a volume"),
              std::string::npos);
}

TEST(GridVolume, ErrorsNameTheSceneLine) {
    const std::string f = rampGrid();
    // Parameters are on lines 6, 7, ... in the order given.
    EXPECT_NE(errorOf([&] { makeVolume("gridvolume", {{"filename", f}, {"filter_type", std::string("cubic")}}); })
                  .find("scene.xml:7: gridvolume: filter_type 'cubic' is not supported"),
              std::string::npos);
    EXPECT_NE(errorOf([&] { makeVolume("gridvolume", {{"filename", f}, {"wrap_mode", std::string("border")}}); })
                  .find("scene.xml:7: gridvolume: wrap_mode 'border'"),
              std::string::npos);
    const std::string missing = errorOf([&] { makeVolume("gridvolume", {{"filename", std::string("/nonexistent/x.vol")}}); });
    EXPECT_NE(missing.find("scene.xml:6: /nonexistent/x.vol: cannot open"), std::string::npos) << missing;
    const std::string four = writeVol("four.vol", ivec3(1), 4, {1, 2, 3, 4});
    EXPECT_NE(errorOf([&] { makeVolume("gridvolume", {{"filename", four}}); }).find("grids of 1, 3 or 6 channels, this one has 4"),
              std::string::npos);
    EXPECT_NE(errorOf([&] { makeVolume("gridvolume", {{"filename", f}, {"to_world", mat4(0.0f)}}); })
                  .find("scene.xml:7: volume 'gridvolume': to_world must be an invertible"),
              std::string::npos);
    const std::string flat = writeVol("flat.vol", ivec3(1), 1, {1}, vec3(0), vec3(1, 0, 1));
    EXPECT_NE(errorOf([&] { makeVolume("gridvolume", {{"filename", flat}, {"use_grid_bbox", true}}); })
                  .find("scene.xml:7: gridvolume: use_grid_bbox needs a non-empty bounding box"),
              std::string::npos);
    EXPECT_NE(errorOf([&] { makeVolume("gridvolume", {{"filename", f}, {"colour", 1.0f}}); }).find("unknown parameter 'colour'"),
              std::string::npos);
}

}  // namespace
}  // namespace iris
