// The polarized form of volpath and volpathmis (integrators/volpath.cpp with Stokes rows,
// integrators/volpath_stokes.h; docs/polarization.md). (1) A scene whose media and surfaces do not
// polarize (HG and isotropic phase functions, diffuse surfaces, null boundaries) renders the same
// image in polarized mode (S0) as in spectral mode, in expectation: Welch's t-test on the image
// means of renders with independent fixed seeds, |t| < 5. (2) Single Rayleigh scattering at 90°
// (an optically thin Rayleigh medium lit from the side) is linearly polarized normal to the plane
// of scattering, the skylight effect: the stokes integrator's S1 ≈ −S0 in its camera basis. The
// spectral walk of these integrators is covered by test_volpath*.cpp and the regression renders.
#include <gtest/gtest.h>

#include <cmath>
#include <algorithm>
#include <string>

#include "render/stokes_film.h"
#include "tests/support/image_mean.h"

using namespace iris;

namespace {

constexpr int kRes = 8;

std::string scene(const std::string& integrator, const std::string& body) {
    return R"(<scene version="3.0.0">
  <integrator type=")" + integrator + R"("/>
  <sensor type="perspective"><float name="fov" value="40"/>
    <transform name="to_world"><lookat origin="0 0 4" target="0 0 0" up="0 1 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/><rfilter type="box"/></film></sensor>
)" + body + "</scene>";
}

/// A sphere of a chromatic HG medium (null boundary) above a diffuse floor, lit by an area light
/// and a dim environment: no element polarizes.
const std::string kNonPolarizing = R"(
  <medium type="homogeneous" id="fog">
    <rgb name="sigma_t" value="1.5, 0.8, 0.4"/><rgb name="albedo" value="0.9, 0.7, 0.8"/>
    <phase type="hg"><float name="g" value="0.4"/></phase></medium>
  <shape type="sphere"><float name="radius" value="0.9"/><bsdf type="null"/><ref name="interior" id="fog"/></shape>
  <shape type="rectangle"><bsdf type="diffuse"><rgb name="reflectance" value="0.7, 0.5, 0.3"/></bsdf>
    <transform name="to_world"><rotate x="1" angle="-90"/><scale value="4"/><translate y="-1"/></transform></shape>
  <shape type="rectangle"><emitter type="area"><rgb name="radiance" value="6, 5, 4"/></emitter>
    <transform name="to_world"><rotate x="1" angle="90"/><translate x="0.5" y="3"/></transform></shape>
  <emitter type="constant"><rgb name="radiance" value="0.2"/></emitter>
)";

Film renderSpectral(const std::string& xml, int spp, uint64_t seed) { return test::renderXml(xml, kRes, kRes, spp, seed, false); }

Film renderPolarized(const std::string& xml, int spp, uint64_t seed, StokesFilm* stokes = nullptr) {
    const Scene s(loadSceneFromString(xml, "."));
    RenderOptions opt;
    opt.spp = spp;
    opt.seed = seed;
    opt.threads = 2;
    opt.polarized = true;
    Film film(kRes, kRes);
    Renderer(s, opt).render(film, nullptr, nullptr, stokes);
    return film;
}

/// The image mean of channel c over K independent renders (seeds seed0 .. seed0 + K − 1): its mean
/// and standard error from the spread of the K values (i.i.d., unlike the pixels of one image).
test::ImageMean meanOverRenders(const std::string& xml, bool polarized, int spp, uint64_t seed0, int c, int K = 12) {
    double s = 0, s2 = 0;
    for (int k = 0; k < K; ++k) {
        const Film f = polarized ? renderPolarized(xml, spp, seed0 + k) : renderSpectral(xml, spp, seed0 + k);
        const double v = test::imageMean(f, c).mean;
        s += v;
        s2 += v * v;
    }
    test::ImageMean m;
    m.mean = s / K;
    m.stderr_ = std::sqrt(std::max(0.0, s2 / K - m.mean * m.mean) / (K - 1));
    return m;
}

/// Welch's t of two independent means.
double welchT(const test::ImageMean& a, const test::ImageMean& b) {
    return (a.mean - b.mean) / std::sqrt(a.stderr_ * a.stderr_ + b.stderr_ * b.stderr_);
}

}  // namespace

TEST(VolPathPolarized, NonPolarizingMediaGiveTheSpectralImage) {
    for (const char* integrator : {"volpath", "volpathmis"}) {
        const std::string xml = scene(integrator, kNonPolarizing);
        for (int c = 0; c < 3; ++c) {
            const test::ImageMean spectral = meanOverRenders(xml, false, 16, 100, c), polarized = meanOverRenders(xml, true, 16, 200, c);
            ASSERT_GT(spectral.mean, 0.05) << integrator;
            EXPECT_LT(std::abs(welchT(spectral, polarized)), 5.0) << integrator << " channel " << c;
        }
    }
}

TEST(VolPathPolarized, TheWelchTestSeesAnImageThatDiffers) {
    // The test above can fail: a medium albedo 20% lower in the polarized render is rejected.
    std::string darker = kNonPolarizing;
    darker.replace(darker.find("0.9, 0.7, 0.8"), 13, "0.72, 0.56, 0.64");
    const test::ImageMean spectral = meanOverRenders(scene("volpath", kNonPolarizing), false, 16, 100, 1);
    const test::ImageMean polarized = meanOverRenders(scene("volpath", darker), true, 16, 200, 1);
    EXPECT_GT(std::abs(welchT(spectral, polarized)), 5.0);
}

TEST(VolPathPolarized, SingleRayleighScatteringAt90DegreesIsPolarizedNormalToThePlane) {
    // A thin slab (optical depth 0.02 along the view) of a Rayleigh medium, lit by a directional
    // light along −x, seen along −z: single scattering dominates, at θ ≈ 90° (fov 10°), so the
    // light is polarized along y, normal to the x-z plane of scattering. The stokes integrator's
    // basis is ray.d × up ≈ (1, 0, 0) (integrators/stokes.cpp), hence S1 ≈ −S0, S2 ≈ S3 ≈ 0.
    const std::string body = R"(
  <medium type="homogeneous" id="air"><float name="sigma_t" value="0.01"/><float name="albedo" value="1"/>
    <phase type="rayleigh"/></medium>
  <shape type="cube"><bsdf type="null"/><ref name="interior" id="air"/></shape>
  <emitter type="directional"><vector name="direction" value="-1, 0, 0"/><float name="irradiance" value="100"/></emitter>
)";
    const auto withIntegrator = [&](const std::string& integrator) {
        return R"(<scene version="3.0.0">
  )" + integrator + R"(
  <sensor type="perspective"><float name="fov" value="10"/>
    <transform name="to_world"><lookat origin="0 0 4" target="0 0 0" up="0 1 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/><rfilter type="box"/></film></sensor>
)" + body + "</scene>";
    };
    const std::string xml = withIntegrator(R"(<integrator type="stokes"><integrator type="volpath"/></integrator>)");
    StokesFilm stokes(kRes, kRes);
    renderPolarized(xml, 16, 5, &stokes);
    double s[4] = {};
    for (int y = 0; y < kRes; ++y)
        for (int x = 0; x < kRes; ++x)
            for (int k = 0; k < 4; ++k) s[k] += stokes.component(k).pixel(x, y).y;
    ASSERT_GT(s[0], 0.0);
    EXPECT_NEAR(s[1] / s[0], -1.0, 0.02);
    EXPECT_NEAR(s[2] / s[0], 0.0, 0.02);
    EXPECT_NEAR(s[3] / s[0], 0.0, 1e-3);
    // The image is S0, and S0 is the spectral mode's single scattering (same phase function value).
    const test::ImageMean spectral = meanOverRenders(withIntegrator(R"(<integrator type="volpath"/>)"), false, 4, 10, 1);
    const test::ImageMean polarized = meanOverRenders(xml, true, 4, 30, 1);
    EXPECT_LT(std::abs(welchT(spectral, polarized)), 5.0);
}

TEST(VolPathPolarized, AnEmittingScatteringMediumKeepsItsClosedForm) {
    // The camera inside an unbounded medium of σ_t = 1, albedo 0.8 with a volumelight j = 0.3
    // (tests/integrators/test_volpath_emission.cpp): L = j / σ_a = 1.5 in polarized mode too, the
    // emission entering the Stokes rows unpolarized (addMediumEmission).
    const std::string xml = R"(<scene version="3.0.0">
  <integrator type="volpath"/>
  <medium type="homogeneous" id="m"><float name="sigma_t" value="1"/><float name="albedo" value="0.8"/>
    <emitter type="volumelight"><float name="radiance" value="0.3"/></emitter></medium>
  <sensor type="perspective"><float name="fov" value="30"/><ref name="medium" id="m"/>
    <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/><rfilter type="box"/></film></sensor>
</scene>)";
    const test::ImageMean m = meanOverRenders(xml, true, 32, 40, 1, 8);
    // A float volumelight radiance is D65 with Y = value (docs/conventions.md): Y = 0.3 / 0.2.
    EXPECT_NEAR(m.mean, 1.5, 5 * m.stderr_ + 5e-3);
}
