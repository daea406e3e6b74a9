// Lights: analytic irradiance from sphere and rectangle area lights through the direct and path
// integrators (tests next-event estimation + MIS), point/directional lights, and the environment
// map's importance sampling (pdf consistency and an unbiased estimate of its integral).
#include <gtest/gtest.h>

#include <bit>
#include <map>
#include <set>

#include "render/film.h"
#include "core/io/image.h"
#include "render/renderer.h"
#include "core/rng.h"
#include "render/scene.h"
#include "tests/support/polygon_irradiance.h"
#include "tests/support/render_test_scenes.h"
#include "spectral/lane_dispatch.h"
#include "spectral/spectrum_factory.h"
#include "render/loader/scene_upgrade.h"
#include "integrators/transport_steps.h"

using namespace iris;
using namespace iris::testing;

namespace {

/// A diffuse floor (z = 0, facing +z) of albedo ρ, seen straight down from above through a tiny
/// field of view so that every pixel sees (nearly) the origin.
SceneDescription floorScene(float albedo) {
    SceneDescription d;
    d.sourceFile = "<floor>";
    ShapeDescription floor;
    floor.mesh = std::make_shared<TriangleMesh>(makeRectangle());
    floor.mesh->transform(glm::scale(mat4(1.0f), vec3(100.0f)));
    floor.material = makeDiffuse(albedo);
    floor.name = "floor";
    d.shapes.push_back(floor);
    // Camera at (0,0,0.5)... looking down −z: Mitsuba frame (x left, y up, z forward).
    mat4 cam(1.0f);
    cam[0] = vec4(-1, 0, 0, 0);
    cam[1] = vec4(0, 1, 0, 0);
    cam[2] = vec4(0, 0, -1, 0);
    cam[3] = vec4(0, 0, 0.5f, 1);
    iris::testing::setCamera(d.camera, cam, 0.01f, 4, 4);
    d.integrator = iris::testing::makeIntegrator("direct", -1);
    return d;
}

double meanY(const Scene& scene, bool rgb, int spp, uint64_t seed, double* stderrOut) {
    RenderOptions opt;
    opt.rgbMode = rgb;
    opt.spp = spp;
    opt.seed = seed;
    Film film(scene.description().camera.width, scene.description().camera.height);
    Renderer(scene, opt).render(film);
    double s = 0, s2 = 0;
    const int n = film.width() * film.height();
    for (int y = 0; y < film.height(); ++y)
        for (int x = 0; x < film.width(); ++x) {
            const double v = film.pixel(x, y)[1];
            s += v;
            s2 += v * v;
        }
    *stderrOut = std::sqrt(std::max(0.0, s2 / n - sqr(s / n)) / n);
    return s / n;
}

ShapeDescription sphereLight(const vec3& c, float r, float L) {
    ShapeDescription s;
    s.type = ShapeDescription::Type::Sphere;
    s.center = c;
    s.radius = r;
    s.emission = std::make_shared<ConstantSpectrum>(L, SpectrumKind::Illuminant);
    s.material = makeDiffuse(0.0f);
    s.name = "light";
    return s;
}

}  // namespace

TEST(Lights, SphereLightIrradianceIsAnalytic) {
    // A sphere of radius r and radiance L at height h above the point: E = π L (r/h)², so the
    // diffuse floor's radiance is ρ/π E = ρ L (r/h)² (the floor point is far from the horizon).
    for (const char* integrator : {"direct", "path"}) {
        SceneDescription d = floorScene(0.5f);
        d.integrator = iris::testing::makeIntegrator(integrator, 2);
        const float r = 0.5f, h = 3.0f, L = 4.0f;
        d.shapes.push_back(sphereLight(vec3(0, 0, h), r, L));
        const Scene scene(std::move(d));
        for (const bool rgb : {true, false}) {
            double se;
            const double m = meanY(scene, rgb, 256, 7, &se);
            EXPECT_NEAR(m, 0.5 * L * sqr(r / h), 5 * se + 1e-4) << integrator << (rgb ? " rgb" : " spectral");
        }
    }
}

TEST(Lights, RectangleLightIrradianceIsAnalytic) {
    // Square light of half-size a at height h, parallel to the floor, centred above the point:
    // E = L Σ_edges ½ β_i cos γ_i (Lambert's polygon formula); for this symmetric case
    // E = 4 L · ½ · atan(a/√(a²+h²))·(a/√(a²+h²))... computed generally below.
    const float a = 1.0f, h = 2.0f, L = 3.0f;
    SceneDescription d = floorScene(0.8f);
    ShapeDescription light;
    light.mesh = std::make_shared<TriangleMesh>(makeRectangle());
    // Face down (−z): flip the rectangle, then move it up.
    light.mesh->flipNormals();
    light.mesh->transform(glm::translate(mat4(1.0f), vec3(0, 0, h)) * glm::scale(mat4(1.0f), vec3(a)));
    light.emission = std::make_shared<ConstantSpectrum>(L, SpectrumKind::Illuminant);
    light.material = makeDiffuse(0.0f);
    d.shapes.push_back(light);
    const Scene scene(std::move(d));
    const double E = test::squareLightIrradiance(a, h, L);
    double se;
    const double m = meanY(scene, true, 256, 9, &se);
    EXPECT_NEAR(m, 0.8 / kPi * E, 5 * se + 1e-4);
}

TEST(Lights, AreaLightPdfIsMeasuredFromTheReferencePoint) {
    // pdfLi(p, wi, hit) must equal sampleLi's pdf for the same direction even when the ray that
    // found the light started between p and the light (after a pass-through surface): it once used
    // the hit's ray parameter as the distance, which made MIS weigh such hits too much.
    SceneDescription d = floorScene(0.5f);
    ShapeDescription rect;
    rect.mesh = std::make_shared<TriangleMesh>(makeRectangle());
    rect.mesh->flipNormals();
    rect.mesh->transform(glm::translate(mat4(1.0f), vec3(0, 0, 3)));
    rect.emission = std::make_shared<ConstantSpectrum>(1.0f, SpectrumKind::Illuminant);
    d.shapes.push_back(rect);
    const Scene scene(std::move(d));
    ASSERT_EQ(scene.lights().size(), 1u);
    const Light& light = *scene.lights()[0];
    const SampledWavelengths wl = SampledWavelengths::sampleVisible(0.5f, 4);
    Pcg32 rng(5, 1);
    int checked = 0;
    for (int i = 0; i < 64; ++i) {
        const vec3 p(0.3f, -0.2f, 0.5f);
        const auto ls = light.sampleLi(p, vec2(rng.uniform(), rng.uniform()), wl);
        if (!ls) continue;
        const float dist = glm::length(ls->pLight - p);
        for (const float start : {0.0f, 0.4f, 0.9f}) {  // where along p → light the ray began
            const auto hit = scene.intersect(Ray(p + start * dist * ls->wi, ls->wi));
            ASSERT_TRUE(hit && hit->areaLight == &light);
            EXPECT_NEAR(light.pdfLi(p, ls->wi, &*hit), ls->pdf, 1e-3f * ls->pdf) << "start " << start;
        }
        ++checked;
    }
    EXPECT_GT(checked, 50);
}

TEST(Lights, PointAndDirectionalLightsAreAnalytic) {
    {
        SceneDescription d = floorScene(0.5f);
        Properties p("emitter", "point", SourceLocation{"<test>", 0});
        p.set("position", PointValue{vec3(0, 0, 2)}, SourceLocation{});
        p.set("intensity", 8.0f, SourceLocation{});
        d.lights.push_back(LightRegistry::instance().create(p));
        const Scene scene(std::move(d));
        double se;
        // L = ρ/π · I cosθ / d² with cosθ = 1, d = 2; deterministic (no variance).
        EXPECT_NEAR(meanY(scene, true, 4, 1, &se), 0.5 / kPi * 8.0 / 4.0, 1e-4);
    }
    {
        SceneDescription d = floorScene(0.5f);
        Properties p("emitter", "directional", SourceLocation{"<test>", 0});
        p.set("direction", VectorValue{vec3(0, std::sin(0.5f), -std::cos(0.5f))}, SourceLocation{});
        p.set("irradiance", 2.0f, SourceLocation{});
        d.lights.push_back(LightRegistry::instance().create(p));
        const Scene scene(std::move(d));
        double se;
        EXPECT_NEAR(meanY(scene, true, 4, 1, &se), 0.5 / kPi * 2.0 * std::cos(0.5), 1e-4);
    }
}

namespace {

/// An environment map light from `img` (written to a temporary EXR) in a scene of format `version`.
LightPtr envmapFromImage(const Image& img, const std::string& name, int version = 3) {
    const std::string path = ::testing::TempDir() + name;
    writeEXR(path, img);
    Properties p("emitter", "envmap", SourceLocation{"<test>", 7});
    p.setFormatVersion(version);
    p.set("filename", std::string(path), SourceLocation{"<test>", 8});
    upgradeObject(p);  // as the loader reads it: the version's convention
    LightPtr light = LightRegistry::instance().create(p);
    std::remove(path.c_str());
    return light;
}

vec3 directionOfUV(double u, double v) {
    const double theta = kPi * v, phi = 2 * kPi * u;
    return vec3(std::sin(theta) * std::sin(phi), std::cos(theta), -std::sin(theta) * std::cos(phi));
}

/// The map's value at (u, v) written out independently of envmap_lattice.h: Mitsuba 3 (version
/// ≥ 2) has column x at u = (x + ½)/W (periodic) and row y at v = y/(H − 1); Mitsuba 0.6 has
/// texel centres (x + ½)/W, (y + ½)/H with the rows clamped at the poles. Bilinear in between.
double referenceValue(const Image& img, int c, double u, double v, bool mitsuba3) {
    const int w = img.width, h = img.height;
    const double a = u * w - 0.5, b = mitsuba3 ? v * (h - 1) : v * h - 0.5;
    const double x0 = std::floor(a), y0 = std::floor(b), fx = a - x0, fy = b - y0;
    auto texel = [&](double x, double y) {
        const int xi = ((int(x) % w) + w) % w, yi = std::clamp(int(y), 0, h - 1);
        return double(img.at(xi, yi, c));
    };
    return (1 - fy) * ((1 - fx) * texel(x0, y0) + fx * texel(x0 + 1, y0)) +
           fy * ((1 - fx) * texel(x0, y0 + 1) + fx * texel(x0 + 1, y0 + 1));
}

/// ∫ L dω of channel c for the reference interpolation: in u the periodic interpolant averages to
/// the row mean, so ∫ = 2π² ∫₀¹ rowMean(v) sin(πv) dv, integrated by the midpoint rule (10⁵ steps).
double referenceIntegral(const Image& img, int c, bool mitsuba3) {
    const int steps = 100000;
    double sum = 0;
    for (int i = 0; i < steps; ++i) {
        const double v = (i + 0.5) / steps;
        double row = 0;
        for (int x = 0; x < img.width; ++x) row += referenceValue(img, c, (x + 0.5) / img.width, v, mitsuba3);
        sum += row / img.width * std::sin(kPi * v);
    }
    return 2 * kPi * kPi * sum / steps;
}

Image brightSpotMap() {
    const int w = 32, h = 16;
    Image img(w, h, 3);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) img.at(x, y, c) = (x == 5 && y == 4) ? 50.0f : 0.2f + 0.1f * c + 0.01f * x;
    return img;
}

}  // namespace

TEST(Lights, EnvironmentMapInterpolatesBilinearlyWhereTheVersionPlacesTexels) {
    // Mitsuba interpolates the map bilinearly (nearest-texel lookup was 2–7 % off Mitsuba 3's
    // references at the background of its test scenes); Mitsuba 0.6 and 3 place the texels
    // differently. Le at random directions equals the independent formula, and the two versions
    // differ from each other (the test can tell them apart).
    const Image img = brightSpotMap();
    const SampledWavelengths wl = SampledWavelengths::rgb(defaultChannelWavelengths());
    for (int version : {0, 2, 3}) {
        const bool m3 = version >= 2;
        const LightPtr env = envmapFromImage(img, "iris_env_bilinear.exr", version);
        Sampler rng(11 + version);
        double maxOther = 0;
        for (int i = 0; i < 2000; ++i) {
            const double u = rng.get1D(), v = 0.002 + 0.996 * rng.get1D();
            const SampledSpectrum L = env->Le(TextureQuery{}, vec3(0.0f), directionOfUV(u, v), wl);
            for (int c = 0; c < 3; ++c) {
                const double ref = referenceValue(img, c, u, v, m3);
                ASSERT_NEAR(L[c], ref, 2e-4 * ref + 1e-5) << "version " << version << " u " << u << " v " << v;
                maxOther = std::max(maxOther, std::abs(referenceValue(img, c, u, v, !m3) - ref));
            }
        }
        EXPECT_GT(maxOther, 1.0) << "the 0.6 and 3 placements must differ near the bright texel";
    }
}

TEST(Lights, EnvironmentMapSamplingIsConsistent) {
    // sampleLi's density equals pdfLi and its radiance Le (except within float rounding of a cell
    // edge), and L/pdf estimates ∫ L dω of the interpolated map without bias, for both placements.
    const Image img = brightSpotMap();
    const SampledWavelengths wl = SampledWavelengths::rgb(defaultChannelWavelengths());
    for (int version : {0, 3}) {
        const LightPtr env = envmapFromImage(img, "iris_env_test.exr", version);
        const double ref = referenceIntegral(img, 1, version >= 2);
        Sampler sampler(42);
        const int n = 200000;
        double s = 0, s2 = 0;
        int mismatches = 0;
        for (int i = 0; i < n; ++i) {
            const auto ls = env->sampleLi(vec3(0.0f), sampler.get2D(), wl);
            ASSERT_TRUE(ls.has_value());
            const bool pdfOk = std::abs(env->pdfLi(vec3(0.0f), ls->wi, nullptr) - ls->pdf) <= 1e-3f * ls->pdf;
            const bool leOk = std::abs(env->Le(TextureQuery{}, vec3(0.0f), ls->wi, wl)[1] - ls->L[1]) <= 1e-4f * ls->L[1] + 1e-6f;
            mismatches += !(pdfOk && leOk);
            const double v = ls->L[1] / ls->pdf;
            s += v;
            s2 += v * v;
        }
        EXPECT_LE(mismatches, n / 1000) << "version " << version;
        const double mean = s / n, se = std::sqrt((s2 / n - mean * mean) / n);
        EXPECT_NEAR(mean, ref, 5 * se + 1e-5 * ref) << "version " << version;
    }
}

TEST(Lights, EnvironmentMapTooSmallForMitsuba3IsRejected) {
    // Mitsuba 3 needs at least 2×3 texels (its first and last rows sit on the poles); a version 3
    // scene with a 4×2 map is refused with the file's location, the same map in 0.6 loads.
    Image img(4, 2, 3);
    for (float& x : img.pixels) x = 1.0f;
    EXPECT_NO_THROW(envmapFromImage(img, "iris_env_small.exr", 0));
    try {
        envmapFromImage(img, "iris_env_small.exr", 3);
        FAIL() << "a 4x2 map in a version 3 scene must be rejected";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("<test>:8"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("2x3"), std::string::npos) << e.what();
    }
}

TEST(Lights, EnvironmentMapSpectralLookupMatchesCornerSpectra) {
    // Spectral mode: texel k has spectrum m_k · S_k(λ), S_k = Σ_corners w_c · S_c(λ) with S_c the
    // Illuminant RGBSpectrum of grid corner c of its chromaticity (envmap_light.cpp). Between
    // texels, Mitsuba 0.6 (version 0) interpolates the spectra, Σ w_k m_k S_k; Mitsuba 3 (version
    // 3) interpolates the normalised spectra and the scales separately, (Σ w_k m_k)(Σ w_k S_k)
    // (its eval_spectrum). The lookup sums the corners' shapes and applies the common D65 factor
    // once; compare with the sum of the corners' own eval().
    const int w = 8, h = 5;
    Image img(w, h, 3);
    const vec3 colours[4] = {vec3(0.75f, 0.25f, 0.125f), vec3(0.5f, 0.5f, 0.5f), vec3(0.0625f, 0.8125f, 2.5f),
                             vec3(0.3125f, 0.0f, 0.0f)};
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) img.at(x, y, c) = colours[(x + y) % 4][c] * float(1 + x);
    constexpr int K = 17;
    auto scaleOf = [&](int x, int y) { return double(std::max({img.at(x, y, 0), img.at(x, y, 1), img.at(x, y, 2)})); };
    auto shapeOf = [&](int x, int y, float lambda) {
        const vec3 c(img.at(x, y, 0), img.at(x, y, 1), img.at(x, y, 2));
        const vec3 g = c / float(scaleOf(x, y)) * float(K - 1);
        const int x0 = std::min(int(g.x), K - 2), y0 = std::min(int(g.y), K - 2), z0 = std::min(int(g.z), K - 2);
        const vec3 f = g - vec3(x0, y0, z0);
        double ref = 0;
        for (int corner = 0; corner < 8; ++corner) {
            const int dx = corner & 1, dy = (corner >> 1) & 1, dz = (corner >> 2) & 1;
            const float wc = (dx ? f.x : 1 - f.x) * (dy ? f.y : 1 - f.y) * (dz ? f.z : 1 - f.z);
            if (wc <= 0) continue;
            const SpectrumPtr s = makeRGBSpectrum(vec3(x0 + dx, y0 + dy, z0 + dz) / float(K - 1), SpectrumKind::Illuminant);
            ref += double(wc) * s->eval(lambda);
        }
        return ref;
    };
    for (int version : {0, 3}) {
        const LightPtr env = envmapFromImage(img, "iris_env_spectral_test.exr", version);
        for (int n : {1, 4, 7, 32}) {
            const SampledWavelengths wl = SampledWavelengths::sampleVisible(0.37f, n);
            for (int y = 0; y + 1 < h; ++y)
                for (int x = 0; x < w; ++x) {
                    // A quarter of the way from column x to x+1 (at u = (x + ½)/W) and half-way
                    // from row y to y+1 (v = y/(H − 1) in Mitsuba 3, (y + ½)/H in 0.6).
                    const double fx = 0.25, fy = 0.5;
                    const double v = version >= 2 ? (y + fy) / (h - 1) : (y + 0.5 + fy) / h;
                    const SampledSpectrum L = env->Le(TextureQuery{}, vec3(0.0f), directionOfUV((x + 0.5 + fx) / w, v), wl);
                    const int xs[4] = {x, (x + 1) % w, x, (x + 1) % w}, ys[4] = {y, y, y + 1, y + 1};
                    const double wk[4] = {(1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy, fx * fy};
                    for (int i = 0; i < n; ++i) {
                        const float lambda = wl.lambda(i);
                        double mixed = 0, shape = 0, scale = 0, largest = 0;
                        for (int k = 0; k < 4; ++k) {
                            const double sk = shapeOf(xs[k], ys[k], lambda), mk = scaleOf(xs[k], ys[k]);
                            mixed += wk[k] * mk * sk;
                            shape += wk[k] * sk;
                            scale += wk[k] * mk;
                            largest = std::max(largest, mk * sk);
                        }
                        const double ref = version >= 2 ? shape * scale : mixed;
                        EXPECT_NEAR(L[i], ref, 2e-6 * ref + 1e-5 * largest + 1e-7)
                            << "version " << version << " cell " << x << "," << y << " lambda " << lambda;
                    }
                }
        }
    }
}

TEST(Lights, EnvironmentMapSpectralLookupIsTheSameInBothLaneBuilds) {
    // The spectral lookup sums the grid nodes' shapes four wavelengths per instruction (baseline
    // x86-64) or eight (AVX2: two nodes at once for N <= 4); both add node by node in the same
    // order, so Le and sampleLi give the same bits in both builds, for maps with grey, saturated,
    // black and bright texels, both versions and several N (odd node counts use the 4-lane tail).
    const int w = 16, h = 9;
    Image img(w, h, 3);
    const vec3 colours[6] = {vec3(0.75f, 0.25f, 0.125f), vec3(0.5f, 0.5f, 0.5f), vec3(0.0625f, 0.8125f, 2.5f),
                             vec3(0.3125f, 0.0f, 0.0f), vec3(0.0f), vec3(40.0f, 31.0f, 2.0f)};
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) img.at(x, y, c) = colours[(x * 7 + y * 3) % 6][c] * (1.0f + 0.1f * float(x ^ y));
    for (int version : {0, 3}) {
        const LightPtr env = envmapFromImage(img, "iris_env_lane_builds.exr", version);
        for (int n : {1, 3, 4, 5, 8, 13, 32}) {
            Sampler rng(uint64_t(100 + n + version));
            for (int i = 0; i < 300; ++i) {
                const SampledWavelengths wl = SampledWavelengths::sampleVisible(rng.get1D(), n);
                const vec3 dir = directionOfUV(rng.get1D(), rng.get1D());
                const vec2 u = rng.get2D();
                SampledSpectrum le[2], li[2];
                for (int baseline = 0; baseline < 2; ++baseline) {
                    lanes::forceBaseline = baseline == 1;
                    le[baseline] = env->Le(TextureQuery{}, vec3(0.0f), dir, wl);
                    const auto ls = env->sampleLi(vec3(0.0f), u, wl);
                    ASSERT_TRUE(ls.has_value());
                    li[baseline] = ls->L;
                }
                lanes::forceBaseline = false;
                for (int k = 0; k < n; ++k) {
                    ASSERT_EQ(le[0][k], le[1][k]) << "version " << version << " n " << n << " lane " << k;
                    ASSERT_EQ(li[0][k], li[1][k]) << "version " << version << " n " << n << " lane " << k;
                }
            }
        }
    }
}

namespace {
/// A lat-long map (identity to_world) that is 1 for directions with world z > 0 and 0 below:
/// u = atan2(x, −z)/2π, so z > 0 is the middle half of the columns, u ∈ (1/4, 3/4).
LightPtr upperHemisphereEnvmap(const std::string& path) {
    const int w = 32, h = 16;
    Image img(w, h, 3);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) img.at(x, y, c) = (x >= w / 4 && x < 3 * w / 4) ? 1.0f : 0.0f;
    writeEXR(path, img);
    Properties p("emitter", "envmap", SourceLocation{"<test>", 0});
    p.set("filename", std::string(path), SourceLocation{});
    return LightRegistry::instance().create(p);
}
}  // namespace

TEST(Lights, EscapedRaysSeeTheEnvironmentInTheirOwnDirection) {
    // Light::Le of an infinite light takes the direction the ray leaves in (the same convention
    // as sampleLi's wi). A camera looking down −z sees the dark half; a floor facing +z under the
    // bright half reflects exactly its albedo (E = π·1, L = ρE/π), whether the light is reached by
    // next-event estimation or by BSDF sampling (MIS combines both). Reading Le at −d instead
    // shows the bright half in the background and loses the BSDF-sampled half of the floor.
    const std::string path = ::testing::TempDir() + "iris_env_upper.exr";
    {
        SceneDescription d = floorScene(0.5f);
        d.shapes.clear();
        d.lights.push_back(upperHemisphereEnvmap(path));
        const Scene scene(std::move(d));
        double se;
        EXPECT_EQ(meanY(scene, true, 4, 3, &se), 0.0);
    }
    {
        SceneDescription d = floorScene(0.5f);
        d.lights.push_back(upperHemisphereEnvmap(path));
        const Scene scene(std::move(d));
        double se;
        const double m = meanY(scene, true, 256, 5, &se);
        EXPECT_NEAR(m, 0.5, 5 * se + 1e-3);
    }
    std::remove(path.c_str());
}

namespace {
/// A map with grey, saturated, black and bright texels (black ones give black radiance nearby).
Image mixedColourMap() {
    const int w = 12, h = 7;
    Image img(w, h, 3);
    const vec3 colours[5] = {vec3(0.75f, 0.25f, 0.125f), vec3(0.5f), vec3(0.0625f, 0.8125f, 2.5f), vec3(0.0f),
                             vec3(40.0f, 31.0f, 2.0f)};
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 3; ++c) img.at(x, y, c) = colours[(x * 3 + y) % 5][c];
    return img;
}

bool sameBits(const SampledSpectrum& a, const SampledSpectrum& b, int n) {
    for (int i = 0; i < n; ++i)
        if (std::bit_cast<uint32_t>(a[i]) != std::bit_cast<uint32_t>(b[i])) return false;
    return true;
}
}  // namespace

TEST(Lights, EnvironmentMapDeferredRadianceIsSampleLisRadiance) {
    // Next-event estimation may take the environment map's sample without its radiance
    // (sampleLiDeferred) and look it up once the sample contributes (deferredRadiance): the same
    // direction, pdf and radiance bits as sampleLi, in RGB and spectral mode, for both placements.
    // The comparison can fail: the radiance read at a wrong (u, v) differs.
    const Image img = mixedColourMap();
    const SampledWavelengths sets[3] = {SampledWavelengths::rgb(defaultChannelWavelengths()), SampledWavelengths::sampleVisible(0.3f, 4),
                                        SampledWavelengths::sampleVisible(0.7f, 8)};
    for (int version : {0, 3}) {
        const LightPtr env = envmapFromImage(img, "iris_env_deferred.exr", version);
        for (const SampledWavelengths& wl : sets) {
            Sampler rng(uint64_t(7 + version));
            int wrongDiffers = 0;
            for (int i = 0; i < 400; ++i) {
                const vec2 u = rng.get2D();
                const auto ls = env->sampleLi(vec3(0.0f), u, wl);
                auto ld = env->sampleLiDeferred(vec3(0.0f), u, wl);
                ASSERT_TRUE(ls && ld);
                EXPECT_FALSE(ls->radianceDeferred);
                ASSERT_TRUE(ld->radianceDeferred);
                ASSERT_EQ(ls->wi, ld->wi);
                ASSERT_EQ(ls->pdf, ld->pdf);
                ASSERT_TRUE(sameBits(env->deferredRadiance(*ld, wl), ls->L, wl.size())) << "version " << version << " sample " << i;
                ASSERT_TRUE(sameBits(env->deferredRadiance(*ls, wl), ls->L, wl.size()));
                ld->uv.x = std::fmod(ld->uv.x + 0.5f, 1.0f);  // deliberately wrong
                wrongDiffers += !sameBits(env->deferredRadiance(*ld, wl), ls->L, wl.size());
            }
            EXPECT_GT(wrongDiffers, 200) << "version " << version;
        }
    }
}

TEST(Lights, ResolveRadianceLooksUpDeferredSamplesAndRejectsBlackOnes) {
    // resolveRadiance (integrators/transport_steps.h) fills in a deferred sample's radiance, keeps
    // a sample that was not deferred (a constant light's), and reports a black radiance as no
    // contribution: an all-black map is rejected after the lookup.
    const SampledWavelengths wl = SampledWavelengths::sampleVisible(0.45f, 4);
    const LightPtr env = envmapFromImage(mixedColourMap(), "iris_env_resolve.exr");
    Image black(8, 5, 3);
    for (float& x : black.pixels) x = 0.0f;
    const LightPtr dark = envmapFromImage(black, "iris_env_resolve_black.exr");
    const LightPtr constant = LightRegistry::instance().create(Properties("emitter", "constant", SourceLocation{"<test>", 1}));
    Sampler rng(11);
    int lit = 0;
    for (int i = 0; i < 200; ++i) {
        const vec2 u = rng.get2D();
        VertexLightSample s;
        s.light = env.get();
        s.ls = *env->sampleLiDeferred(vec3(0.0f), u, wl);
        const SampledSpectrum expected = env->sampleLi(vec3(0.0f), u, wl)->L;
        EXPECT_EQ(resolveRadiance(s, wl), !expected.isBlack());
        EXPECT_FALSE(s.ls.radianceDeferred);
        EXPECT_TRUE(sameBits(s.ls.L, expected, wl.size()));
        lit += !expected.isBlack();

        VertexLightSample d;
        d.light = dark.get();
        d.ls = *dark->sampleLiDeferred(vec3(0.0f), u, wl);
        EXPECT_FALSE(resolveRadiance(d, wl));

        VertexLightSample c;
        c.light = constant.get();
        c.ls = *constant->sampleLiDeferred(vec3(0.0f), u, wl);
        EXPECT_FALSE(c.ls.radianceDeferred);
        const SampledSpectrum before = c.ls.L;
        EXPECT_TRUE(resolveRadiance(c, wl));
        EXPECT_TRUE(sameBits(c.ls.L, before, wl.size()));
    }
    EXPECT_GT(lit, 100);
}

TEST(Lights, LightChoiceReusesItsSampleSoEachLightKeepsItsStrata) {
    // chooseLight (integrators/transport_steps.h) picks light i of n with u ∈ [i/n, (i+1)/n) and
    // hands on u·n − i, as both Mitsubas do: n·m stratified values of u give every light m values
    // that again fall one in each of m strata. The raw u (a choice that does not stretch its
    // sample) is the control: its values for one light crowd into 1/n of the strata.
    SceneDescription d = floorScene(0.5f);
    for (int i = 0; i < 3; ++i) d.shapes.push_back(sphereLight(vec3(float(i), 0, 3), 0.5f, 1.0f));
    const Scene scene(std::move(d));
    ASSERT_EQ(scene.lights().size(), 3u);
    const int n = 3, m = 64;
    std::map<const Light*, std::set<int>> reusedStrata, rawStrata;
    for (int k = 0; k < n * m; ++k) {
        const float u = (float(k) + 0.5f) / float(n * m);
        const LightChoice c = chooseLight(scene, u);
        ASSERT_NE(c.light, nullptr);
        EXPECT_FLOAT_EQ(c.pmf, 1.0f / 3.0f);
        ASSERT_GE(c.uReused, 0.0f);
        ASSERT_LT(c.uReused, 1.0f);
        EXPECT_EQ(c.light, scene.lights()[size_t(k / m)].get());
        reusedStrata[c.light].insert(int(c.uReused * m));
        rawStrata[c.light].insert(int(u * m));
    }
    for (const auto& [light, strata] : reusedStrata) EXPECT_EQ(strata.size(), size_t(m));
    for (const auto& [light, strata] : rawStrata) EXPECT_LE(strata.size(), size_t(m / n + 1));
    // The end of the range stays inside it.
    EXPECT_LT(chooseLight(scene, kOneMinusEpsilon).uReused, 1.0f);
    EXPECT_EQ(chooseLight(scene, kOneMinusEpsilon).light, scene.lights()[2].get());
}
