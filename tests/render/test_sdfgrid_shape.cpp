// The sdfgrid shape in scenes (render/shapes/sdfgrid.cpp, render/scene.cpp): Scene hits of a
// sampled sphere placed by to_world, and by an instance, lie on the exact sphere within the grid's
// interpolation error; rays spawned from a hit do not find their own surface again (a white
// furnace stays at the albedo); a lit sdfgrid sphere renders as the analytic sphere does within a
// tolerance from the grid's resolution (and a displaced one does not); bad grids and uses Mitsuba 3
// does not allow are refused with their lines.
#include <gtest/gtest.h>

#include <cmath>

#include "core/rng.h"
#include "core/sampling.h"
#include "render/loader/scene_loader.h"
#include "render/scene.h"
#include "tests/support/error_of.h"
#include "tests/support/image_mean.h"
#include "tests/support/sdf_sphere.h"

using namespace iris;
using namespace iris::test;

namespace {

constexpr int kN = 32;
const vec3 kCentre(0.5f);
constexpr float kRadius = 0.3f;

std::string sphereFile(const vec3& c = kCentre, float r = kRadius) { return writeSphereSdf("iris_sdfgrid_shape", "sphere.vol", kN, c, r); }

std::string scene(const std::string& body) { return "<scene version=\"3.0.0\">\n" + body + "</scene>\n"; }

std::string sdfShape(const std::string& file, const std::string& inner = "") {
    return "<shape type=\"sdfgrid\"><string name=\"filename\" value=\"" + file + "\"/>" + inner + "</shape>\n";
}

/// A to_world of scale 2 and translation (1, 0, 0): the sphere's world centre is (2, 1, 1), radius 0.6.
const std::string kPlace = "<transform name=\"to_world\"><scale value=\"2\"/><translate x=\"1\"/></transform>";
const vec3 kWorldCentre(2, 1, 1);
constexpr float kWorldRadius = 0.6f;

/// Hits of rays towards the placed sphere: the largest distance of a hit from the exact sphere and
/// the largest angle between the geometric normal and the sphere's.
std::pair<double, double> sphereHitErrors(const Scene& s) {
    Pcg32 rng(3, 9);
    double worstP = 0, worstN = 0;
    for (int i = 0; i < 300; ++i) {
        const vec3 o = kWorldCentre + 3.0f * sampleUniformSphere(vec2(rng.uniform(), rng.uniform()));
        const vec3 target = kWorldCentre + 0.5f * sampleUniformSphere(vec2(rng.uniform(), rng.uniform()));
        const auto si = s.intersect(Ray(o, glm::normalize(target - o)));
        if (!si) return {1e9, 1e9};
        worstP = std::max(worstP, std::abs(double(glm::length(si->p - kWorldCentre)) - kWorldRadius));
        worstN = std::max(worstN, double(std::acos(std::min(1.0f, glm::dot(si->ng, glm::normalize(si->p - kWorldCentre))))));
    }
    return {worstP, worstN};
}

}  // namespace

TEST(SdfGridShape, HitsOnThePlacedAndTheInstancedGridLieOnTheSphere) {
    const std::string f = sphereFile();
    const double bound = 2 * sphereSdfPositionBound(kN, kRadius);  // to_world scales by 2
    const Scene placed(loadSceneFromString(scene(sdfShape(f, kPlace)), "."));
    const auto [pPlaced, nPlaced] = sphereHitErrors(placed);
    EXPECT_LT(pPlaced, bound);
    EXPECT_LT(nPlaced, sphereSdfNormalBound(kN, kRadius));
    const Scene instanced(loadSceneFromString(scene("<shape type=\"shapegroup\" id=\"g\">" + sdfShape(f) + "</shape>\n"
                                                    "<shape type=\"instance\"><ref id=\"g\"/>" + kPlace + "</shape>\n"),
                                              "."));
    const auto [pInst, nInst] = sphereHitErrors(instanced);
    EXPECT_LT(pInst, bound);
    EXPECT_LT(nInst, sphereSdfNormalBound(kN, kRadius));
}

TEST(SdfGridShape, SpawnedRaysDoNotFindTheirOwnSurface) {
    const Scene s(loadSceneFromString(scene(sdfShape(sphereFile(), kPlace)), "."));
    Pcg32 rng(5, 1);
    for (int i = 0; i < 300; ++i) {
        const vec3 o = kWorldCentre + 3.0f * sampleUniformSphere(vec2(rng.uniform(), rng.uniform()));
        const auto si = s.intersect(Ray(o, glm::normalize(kWorldCentre + 0.5f * sampleUniformSphere(vec2(rng.uniform(), rng.uniform())) - o)));
        ASSERT_TRUE(si);
        const vec3 out = glm::normalize(si->ng + 0.9f * sampleUniformSphere(vec2(rng.uniform(), rng.uniform())));
        if (glm::dot(out, si->ng) > 0.01f) EXPECT_FALSE(s.intersect(si->spawnRay(out))) << i;
        const vec3 in = -glm::normalize(si->ng + 0.5f * sampleUniformSphere(vec2(rng.uniform(), rng.uniform())));
        const auto far = s.intersect(si->spawnRay(in));
        ASSERT_TRUE(far) << i;
        const float chord = 2 * kWorldRadius * glm::dot(-in, glm::normalize(si->p - kWorldCentre));
        EXPECT_GT(far->t, 0.5f * chord) << i;  // the far side, not the surface the ray left
    }
}

TEST(SdfGridShape, WhiteFurnaceStaysAtTheAlbedo) {
    // A convex diffuse shape in a uniform environment of radiance 1 reflects exactly its albedo:
    // rays that hit their own surface again would darken it.
    const std::string xml = scene(sdfShape(sphereFile(), "<bsdf type=\"diffuse\"><rgb name=\"reflectance\" value=\"0.5\"/></bsdf>") +
                                  "<emitter type=\"constant\"><rgb name=\"radiance\" value=\"1, 1, 1\"/></emitter>\n"
                                  "<sensor type=\"perspective\"><float name=\"fov\" value=\"20\"/><transform name=\"to_world\">"
                                  "<lookat origin=\"0.5, 0.5, -1.5\" target=\"0.5, 0.5, 0.5\" up=\"0, 1, 0\"/></transform>"
                                  "<film type=\"hdrfilm\"><integer name=\"width\" value=\"16\"/><integer name=\"height\" value=\"16\"/>"
                                  "<rfilter type=\"box\"/></film></sensor>\n<integrator type=\"path\"/>\n");
    const Film film = renderXml(xml, 16, 16, 64, 7, true);
    // The central 6×6 pixels lie on the sphere (it spans about 10 of the 16 pixels).
    double s = 0, s2 = 0;
    for (int y = 5; y < 11; ++y)
        for (int x = 5; x < 11; ++x) {
            const double v = film.pixel(x, y)[1];
            s += v, s2 += v * v;
        }
    const double mean = s / 36, se = std::sqrt((s2 / 36 - mean * mean) / 35);
    EXPECT_NEAR(mean, 0.5, 5 * se + 1e-3);
}

TEST(SdfGridShape, LitSphereRendersAsTheAnalyticSphere) {
    // Lit from the camera by a directional light, with the direct integrator and 1 sample per
    // pixel at the same positions in every render (same seed): a pixel is ρE/π·max(0, n·l),
    // deterministic. Where both renders see the sphere, the values differ by at most ρE/π times the
    // normal's angle error bound; pixels whose sample lies within the position bound of the
    // silhouette (seen by a sphere of radius r + δ but not r − δ) may differ completely.
    const double delta = sphereSdfPositionBound(kN, kRadius), tol = 0.8 / M_PI * sphereSdfNormalBound(kN, kRadius);
    auto render = [](const std::string& shape) {
        return renderXml(scene(shape + "<emitter type=\"directional\"><vector name=\"direction\" value=\"0, 0, 1\"/>"
                                       "<rgb name=\"irradiance\" value=\"1, 1, 1\"/></emitter>\n"
                                       "<sensor type=\"perspective\"><float name=\"fov\" value=\"30\"/><transform name=\"to_world\">"
                                       "<lookat origin=\"0.5, 0.5, -1.5\" target=\"0.5, 0.5, 0.5\" up=\"0, 1, 0\"/></transform>"
                                       "<film type=\"hdrfilm\"><integer name=\"width\" value=\"48\"/><integer name=\"height\" value=\"48\"/>"
                                       "<rfilter type=\"box\"/></film></sensor>\n<integrator type=\"direct\"/>\n"),
                         48, 48, 1, 3, true);
    };
    const std::string bsdf = "<bsdf type=\"diffuse\"><rgb name=\"reflectance\" value=\"0.8\"/></bsdf>";
    auto sphere = [&](float r) {
        return "<shape type=\"sphere\"><point name=\"center\" value=\"0.5, 0.5, 0.5\"/><float name=\"radius\" value=\"" +
               std::to_string(r) + "\"/>" + bsdf + "</shape>\n";
    };
    const Film exact = render(sphere(kRadius)), outer = render(sphere(kRadius + float(delta))), inner = render(sphere(kRadius - float(delta)));
    auto compare = [&](const Film& sdf, int& silhouette) {
        double worst = 0;
        silhouette = 0;
        for (int y = 0; y < 48; ++y)
            for (int x = 0; x < 48; ++x) {
                if (outer.pixel(x, y)[1] > 0 && inner.pixel(x, y)[1] == 0) {
                    ++silhouette;
                    continue;
                }
                worst = std::max(worst, double(std::abs(sdf.pixel(x, y)[1] - exact.pixel(x, y)[1])));
            }
        return worst;
    };
    int silhouette = 0;
    for (const char* normals : {"smooth", "analytic"}) {
        const Film sdf = render(sdfShape(sphereFile(), std::string("<string name=\"normals\" value=\"") + normals + "\"/>" + bsdf));
        EXPECT_LT(compare(sdf, silhouette), tol) << normals;
        EXPECT_LT(silhouette, 48) << normals;  // a thin band (about one pixel a row at most): the bound excuses little
    }
    // The sphere moved by two voxels is told apart.
    const Film moved = render(sdfShape(sphereFile(kCentre + vec3(2.0f / (kN - 1), 0, 0)), bsdf));
    EXPECT_GT(compare(moved, silhouette), tol);
}

TEST(SdfGridShape, BadGridsAndUsesAreRefusedWithTheirLine) {
    const std::string dir = "iris_sdfgrid_shape";
    const std::string rgb = writeVolFile(dir, "rgb.vol", ivec3(2), 3, std::vector<float>(24, -1.0f));
    const std::string flat = writeVolFile(dir, "flat.vol", ivec3(1, 4, 4), 1, std::vector<float>(16, -1.0f));
    std::vector<float> nan = sphereSdfSamples(4, kCentre, kRadius);
    nan[5] = std::nanf("");
    const std::string bad = writeVolFile(dir, "nan.vol", ivec3(4), 1, nan);
    const std::string empty = writeVolFile(dir, "empty.vol", ivec3(3), 1, std::vector<float>(27, 1.0f));
    auto err = [&](const std::string& body) { return errorOf([&] { loadSceneFromString(scene(body), "."); }); };
    EXPECT_TRUE(contains(err(sdfShape(rgb)), "<string>:2: " + rgb + ": an sdfgrid needs a 1-channel grid, this one has 3 channels"));
    EXPECT_TRUE(contains(err(sdfShape(flat)), "<string>:2: " + flat + ": an sdfgrid needs at least 2 samples along each axis"));
    EXPECT_TRUE(contains(err(sdfShape(bad)), "<string>:2: " + bad + ": non-finite .vol value"));
    EXPECT_TRUE(contains(err(sdfShape(empty)), "<string>:2: " + empty + ": the sdfgrid has no surface"));
    EXPECT_TRUE(contains(err(sdfShape("/nonexistent/x.vol")), "<string>:2: file '/nonexistent/x.vol' not found"));
    EXPECT_TRUE(contains(err("<shape type=\"sdfgrid\"/>\n"), "missing required parameter 'filename'"));
    const std::string f = sphereFile();
    EXPECT_TRUE(contains(err(sdfShape(f, "\n<string name=\"normals\" value=\"flat\"/>")),
                         "<string>:3: sdfgrid: normals 'flat' is not supported (supported: smooth, analytic)"));
    EXPECT_TRUE(contains(err(sdfShape(f, "\n<emitter type=\"area\"><rgb name=\"radiance\" value=\"1, 1, 1\"/></emitter>")),
                         "<string>:3: an sdfgrid cannot be an area emitter"));
    // A medium needs a closed surface: a sphere the grid's boundary cuts is not.
    const std::string medium = "<medium type=\"homogeneous\" id=\"m\"/>\n";
    const std::string cut = writeSphereSdf(dir, "cut.vol", 8, vec3(0.5f), 0.6f);
    EXPECT_TRUE(contains(err(medium + sdfShape(cut, "<ref name=\"interior\" id=\"m\"/>")), "its sdfgrid surface reaches the grid's boundary"));
    EXPECT_EQ(err(medium + sdfShape(f, "<ref name=\"interior\" id=\"m\"/>") + "<integrator type=\"volpath\"/>\n"), "");
}
