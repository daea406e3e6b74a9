// The heterogeneous medium (media/heterogeneous.cpp) and its majorant grid
// (media/majorant_grid.h), created through MediumRegistry from Properties built in code:
//  - the majorant bounds σ_t at every point of every segment, in every lane (random rays, dense
//    sampling of each segment and its ends), for axis-aligned and rotated to_world, every filter
//    and wrap mode, scalar and RGB grids;
//  - segments are in order, do not overlap and cover the ray's piece inside the box (gaps only
//    where σ_t = 0); a ray that misses the box has none;
//  - ratio tracking over the segments (fixed seed) estimates the transmittance exp(−∫σ_t) that a
//    fine quadrature gives, within 4 standard errors of the estimator;
//  - parameter errors carry the scene line.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <vector>

#include "core/rng.h"
#include "media/majorant_grid.h"
#include "media/medium.h"
#include "tests/support/error_of.h"
#include "tests/support/vol_file.h"

namespace iris {
namespace {

using test::errorOf;
using Param = std::pair<std::string, PropertyValue>;

const SampledWavelengths kRGB = SampledWavelengths::rgb(defaultChannelWavelengths());

std::string writeVol(const std::string& name, ivec3 res, int channels, const std::vector<float>& v) {
    return test::writeVolFile("iris_heterogeneous_test", name, res, channels, v);
}

/// Random values in [lo, hi) (fixed seed); zeroFraction of the voxels set to 0.
std::string randomGrid(const std::string& name, ivec3 res, int channels, float lo, float hi, uint64_t seed,
                       float zeroFraction = 0.0f) {
    Pcg32 rng(seed, 11);
    std::vector<float> v(size_t(res.x * res.y * res.z * channels));
    for (float& x : v) x = rng.uniform() < zeroFraction ? 0.0f : lo + (hi - lo) * rng.uniform();
    return writeVol(name, res, channels, v);
}

std::shared_ptr<Properties> props(const std::string& tag, const std::string& type, std::initializer_list<Param> params) {
    auto p = std::make_shared<Properties>(tag, type, SourceLocation{"scene.xml", 3});
    int line = 4;
    for (const auto& [name, value] : params) p->set(name, value, SourceLocation{"scene.xml", line++});
    return p;
}

MediumPtr makeMedium(std::initializer_list<Param> params) {
    return MediumRegistry::instance().create(*props("medium", "heterogeneous", params));
}

std::vector<MajorantSegment> segments(const Medium& m, const Ray& r, float tMax, const SampledWavelengths& wl, Arena& arena) {
    std::vector<MajorantSegment> out;
    MajorantIterator* it = m.majorants(r, tMax, wl, arena);
    while (auto s = it->next()) out.push_back(*s);
    return out;
}

vec3 randomDir(Pcg32& rng) {
    const float z = 1 - 2 * rng.uniform(), phi = 2 * kPi * rng.uniform(), r = safeSqrt(1 - z * z);
    return vec3(r * std::cos(phi), r * std::sin(phi), z);
}

/// A ray from a random point near the box (inside or out) in a random direction.
Ray randomRay(Pcg32& rng, const Box3& box) {
    const vec3 size = box.hi - box.lo;
    const vec3 o = box.lo - 0.5f * size + 2.0f * size * vec3(rng.uniform(), rng.uniform(), rng.uniform());
    return Ray(o, randomDir(rng));
}

struct Case {
    const char* name;
    mat4 toWorld;
    const char* filter;
    const char* wrap;
    int channels;
    float zeroFraction;
};

std::vector<Case> cases() {
    const mat4 stretch = glm::scale(glm::translate(mat4(1.0f), vec3(-1.0f, -0.5f, 0.3f)), vec3(2.0f, 1.5f, 0.8f));
    const mat4 rotated = glm::rotate(stretch, 0.7f, glm::normalize(vec3(1, 2, 3)));
    return {{"axis-aligned trilinear", stretch, "trilinear", "clamp", 1, 0.0f},
            {"axis-aligned nearest sparse", stretch, "nearest", "clamp", 1, 0.6f},
            {"rotated trilinear clamp", rotated, "trilinear", "clamp", 1, 0.0f},
            {"rotated trilinear repeat", rotated, "trilinear", "repeat", 1, 0.3f},
            {"rotated nearest mirror", rotated, "nearest", "mirror", 1, 0.0f},
            {"axis-aligned RGB", stretch, "trilinear", "clamp", 3, 0.0f}};
}

MediumPtr caseMedium(const Case& c, int index) {
    const std::string f = randomGrid("case" + std::to_string(index) + ".vol", ivec3(13, 7, 9), c.channels, 0.1f, 2.0f,
                                     uint64_t(index) + 1, c.zeroFraction);
    auto vol = props("volume", "gridvolume", {{"filename", f}, {"filter_type", std::string(c.filter)},
                                             {"wrap_mode", std::string(c.wrap)}, {"to_world", c.toWorld}});
    return makeMedium({{"sigma_t", vol}, {"scale", 3.0f}, {"albedo", 0.8f}});
}

Box3 caseBox(const Case& c) { return transformBox(c.toWorld, Box3{vec3(0), vec3(1)}); }

TEST(HeterogeneousMedium, MajorantBoundsSigmaTEverywhere) {
    const SampledWavelengths spectral = SampledWavelengths::sampleVisible(0.37f, 8);
    const std::vector<Case> cs = cases();
    for (size_t ci = 0; ci < cs.size(); ++ci) {
        const Case& c = cs[ci];
        const MediumPtr m = caseMedium(c, int(ci));
        const Box3 box = caseBox(c);
        Pcg32 rng(ci + 100, 5);
        Arena arena;
        for (const SampledWavelengths& wl : {kRGB, spectral})
            for (int r = 0; r < 300; ++r) {
                arena.reset();
                const Ray ray = randomRay(rng, box);
                const float tMax = 10.0f * rng.uniform() + 0.1f;
                float prevEnd = 0.0f;
                for (const MajorantSegment& s : segments(*m, ray, tMax, wl, arena)) {
                    ASSERT_LT(s.tMin, s.tMax) << c.name;
                    ASSERT_GE(s.tMin, prevEnd) << c.name;  // in order, not overlapping
                    ASSERT_LE(s.tMax, tMax) << c.name;
                    ASSERT_EQ(s.sigmaMaj.size(), wl.size());
                    // σ_t = 0 in the gap before this segment.
                    for (int k = 1; k < 8; ++k) {
                        const float t = prevEnd + (s.tMin - prevEnd) * float(k) / 8;
                        if (s.tMin - prevEnd > 1e-4f)
                            ASSERT_TRUE(m->coefficients(ray.at(t), wl).sigmaT.isBlack()) << c.name << " gap at " << t;
                    }
                    for (int k = 0; k <= 64; ++k) {
                        const float t = s.tMin + (s.tMax - s.tMin) * float(k) / 64;
                        const MediumCoefficients co = m->coefficients(ray.at(t), wl);
                        for (int l = 0; l < wl.size(); ++l) {
                            ASSERT_LE(co.sigmaT[l], s.sigmaMaj[l] * (1 + 1e-5f)) << c.name << " t " << t << " lane " << l;
                            ASSERT_GE(co.sigmaT[l], 0.0f);
                            ASSERT_NEAR(co.sigmaS[l], 0.8f * co.sigmaT[l], 1e-5f * co.sigmaT[l] + 1e-7f);
                        }
                    }
                    prevEnd = s.tMax;
                }
                // σ_t = 0 after the last segment.
                for (int k = 1; k <= 16; ++k) {
                    const float t = prevEnd + (tMax - prevEnd) * float(k) / 16;
                    if (tMax - prevEnd > 1e-4f) ASSERT_TRUE(m->coefficients(ray.at(t), wl).sigmaT.isBlack()) << c.name;
                }
            }
    }
}

TEST(HeterogeneousMedium, SegmentsCoverTheBox) {
    const Case c = cases()[2];  // rotated, no zero voxels: no gaps
    const MediumPtr m = caseMedium(c, 2);
    const Box3 box = caseBox(c);
    Pcg32 rng(9, 9);
    Arena arena;
    int hits = 0;
    for (int r = 0; r < 500; ++r) {
        arena.reset();
        const Ray ray = randomRay(rng, box);
        const std::vector<MajorantSegment> segs = segments(*m, ray, 1e30f, kRGB, arena);
        float t0, t1;
        if (!box.clip(ray, 1e30f, t0, t1) || t1 - t0 < 1e-5f) continue;
        ++hits;
        ASSERT_FALSE(segs.empty());
        EXPECT_FLOAT_EQ(segs.front().tMin, t0);
        EXPECT_FLOAT_EQ(segs.back().tMax, t1);
        for (size_t i = 1; i < segs.size(); ++i) ASSERT_EQ(segs[i].tMin, segs[i - 1].tMax);
    }
    EXPECT_GT(hits, 100);
}

TEST(HeterogeneousMedium, RayMissingTheBoxHasNoSegments) {
    const MediumPtr m = caseMedium(cases()[0], 0);
    Arena arena;
    EXPECT_TRUE(segments(*m, Ray(vec3(5, 5, 5), vec3(0, 0, 1)), 100.0f, kRGB, arena).empty());
    EXPECT_TRUE(segments(*m, Ray(vec3(0, 0, -0.5f), vec3(0, 0, -1)), 100.0f, kRGB, arena).empty());  // box behind
    EXPECT_TRUE(segments(*m, Ray(vec3(0, 0, -5), vec3(0, 0, 1)), 1.0f, kRGB, arena).empty());      // too short
    EXPECT_TRUE(m->coefficients(vec3(5, 5, 5), kRGB).sigmaT.isBlack());
}

TEST(HeterogeneousMedium, ConstantSigmaTFillsTheUnitCube) {
    // A number for sigma_t is a constvolume: to_world's unit cube, [0,1]³ (Mitsuba 3).
    const MediumPtr m = makeMedium({{"sigma_t", 2.0f}, {"scale", 1.5f}});
    EXPECT_FLOAT_EQ(m->coefficients(vec3(0.5f), kRGB).sigmaT[1], 3.0f);
    EXPECT_FLOAT_EQ(m->coefficients(vec3(0.5f), kRGB).sigmaS[1], 3.0f * 0.75f);  // default albedo
    EXPECT_TRUE(m->coefficients(vec3(1.5f, 0.5f, 0.5f), kRGB).sigmaT.isBlack());
    Arena arena;
    const std::vector<MajorantSegment> s = segments(*m, Ray(vec3(-1, 0.5f, 0.5f), vec3(1, 0, 0)), 10.0f, kRGB, arena);
    ASSERT_EQ(s.size(), 1u);
    EXPECT_FLOAT_EQ(s[0].tMin, 1.0f);
    EXPECT_FLOAT_EQ(s[0].tMax, 2.0f);
    EXPECT_FLOAT_EQ(s[0].sigmaMaj[0], 3.0f);  // exact: no null collisions
    // An RGB sigma_t: per-lane majorants equal σ_t.
    const MediumPtr rgb = makeMedium({{"sigma_t", RGBValue{vec3(1, 2, 3)}}});
    const std::vector<MajorantSegment> r = segments(*rgb, Ray(vec3(0.5f, 0.5f, -1), vec3(0, 0, 1)), 10.0f, kRGB, arena);
    ASSERT_EQ(r.size(), 1u);
    EXPECT_FLOAT_EQ(r[0].sigmaMaj[2], 3.0f);
    // Default phase and sample_emitters.
    EXPECT_TRUE(m->sampleEmitters());
    EXPECT_FALSE(makeMedium({{"sample_emitters", false}})->sampleEmitters());
}

/// Ratio tracking (Cramer 1978; Novák et al. 2014 §4.2) over the segments: per lane-0 majorant,
/// T̂ = Π over tentative collisions (1 − σ_t/σ_maj).
double ratioTracking(const Medium& m, const Ray& ray, float tMax, Pcg32& rng, Arena& arena) {
    double T = 1.0;
    MajorantIterator* it = m.majorants(ray, tMax, kRGB, arena);
    while (auto s = it->next()) {
        const float maj = s->sigmaMaj[0];
        for (float t = s->tMin;;) {
            t += -std::log(1.0f - rng.uniform()) / maj;
            if (t >= s->tMax) break;
            T *= 1.0 - double(m.coefficients(ray.at(t), kRGB).sigmaT[0]) / maj;
        }
    }
    return T;
}

/// ∫σ_t along the ray over [0, tMax] by the composite midpoint rule.
double opticalDepth(const Medium& m, const Ray& ray, float tMax, int n) {
    double sum = 0.0;
    for (int i = 0; i < n; ++i) sum += m.coefficients(ray.at((float(i) + 0.5f) * tMax / float(n)), kRGB).sigmaT[0];
    return sum * tMax / n;
}

TEST(HeterogeneousMedium, RatioTrackingMatchesQuadrature) {
    const std::vector<Case> cs = cases();
    for (size_t ci : {size_t(0), size_t(3)}) {
        const Case& c = cs[ci];
        const MediumPtr m = caseMedium(c, int(ci));
        const Box3 box = caseBox(c);
        const vec3 centre = 0.5f * (box.lo + box.hi);
        Pcg32 rng(ci + 7, 1);
        Arena arena;
        for (int r = 0; r < 4; ++r) {
            const vec3 d = randomDir(rng);
            const Ray ray(centre - 3.0f * d, d);
            const float tMax = 6.0f;
            const double depth = opticalDepth(*m, ray, tMax, 200000), exact = std::exp(-depth);
            EXPECT_GT(depth, 0.3) << c.name;  // the ray crosses the medium
            const int n = 20000;
            double sum = 0, sum2 = 0;
            for (int i = 0; i < n; ++i) {
                arena.reset();
                const double T = ratioTracking(*m, ray, tMax, rng, arena);
                sum += T, sum2 += T * T;
            }
            const double mean = sum / n, se = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n);
            EXPECT_NEAR(mean, exact, 4.0 * se + 1e-4) << c.name << " ray " << r << " se " << se;
        }
    }
}

TEST(HeterogeneousMedium, ErrorsCarryTheSceneLine) {
    const std::string ok = randomGrid("ok.vol", ivec3(2), 1, 0.0f, 1.0f, 1);
    const std::string negative = writeVol("negative.vol", ivec3(2, 1, 1), 1, {0.5f, -0.25f});
    const std::string bright = writeVol("bright.vol", ivec3(2, 1, 1), 1, {0.5f, 1.5f});
    // Parameters are on lines 4, 5, ... in the order given.
    EXPECT_NE(errorOf([&] { makeMedium({{"scale", -1.0f}}); }).find("scene.xml:4: heterogeneous: scale must be"),
              std::string::npos);
    const std::string neg = errorOf([&] { makeMedium({{"sigma_t", props("volume", "gridvolume", {{"filename", negative}})}}); });
    EXPECT_NE(neg.find("scene.xml:4: heterogeneous: sigma_t has negative values (minimum -0.25)"), std::string::npos) << neg;
    EXPECT_NE(errorOf([&] { makeMedium({{"scale", 2.0f}, {"albedo", 1.5f}}); }).find("scene.xml:5: heterogeneous: albedo must lie in [0, 1]"),
              std::string::npos);
    EXPECT_NE(errorOf([&] { makeMedium({{"albedo", props("volume", "gridvolume", {{"filename", bright}})}}); })
                  .find("scene.xml:4: heterogeneous: albedo must lie in [0, 1]"),
              std::string::npos);
    const std::string missing = errorOf([&] {
        makeMedium({{"sigma_t", props("volume", "gridvolume", {{"filename", std::string("/nonexistent/smoke.vol")}})}});
    });
    EXPECT_NE(missing.find("scene.xml:4: /nonexistent/smoke.vol: cannot open"), std::string::npos) << missing;
    const std::string truncated = writeVol("truncated.vol", ivec3(4), 1, {1, 2, 3});
    const std::string trunc = errorOf([&] { makeMedium({{"sigma_t", props("volume", "gridvolume", {{"filename", truncated}})}}); });
    EXPECT_NE(trunc.find("scene.xml:4: " + truncated + ": truncated .vol data"), std::string::npos) << trunc;
    EXPECT_NE(errorOf([&] { makeMedium({{"sigma_t", props("volume", "gridvolume", {{"filename", ok}})}, {"density", 1.0f}}); })
                  .find("unknown parameter 'density'"),
              std::string::npos);
}

}  // namespace
}  // namespace iris
