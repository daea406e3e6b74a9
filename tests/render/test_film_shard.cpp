// Split renders: the film's fixed-point sums are order-independent, so the films of disjoint sample
// ranges add up to the unsplit film bit for bit; mergeFilmShards refuses shards that do not form
// one complete render (overlap, gap, other seed, interrupted shard) and names the file.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <functional>

#include "core/error.h"
#include "core/rng.h"
#include "render/film_shard.h"
#include "render/renderer.h"
#include "render/scene.h"
#include "tests/support/render_test_scenes.h"

using namespace iris;
using namespace iris::testing;

namespace {

std::string tempState(const std::string& name) { return ::testing::TempDir() + "iris_shard_" + name + ".state"; }

/// Render samples [begin, end) of the furnace scene into a film state file; returns its path.
std::string renderShard(const Scene& scene, RenderOptions opt, int begin, int end, const std::string& name) {
    opt.firstSample = begin;
    opt.spp = end - begin;
    opt.checkpointPath = tempState(name);
    Film film(scene.description().camera.width, scene.description().camera.height);
    Renderer(scene, opt).render(film);
    return opt.checkpointPath;
}

std::string messageOf(const std::function<void()>& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(FilmShard, FixedPointSumsDoNotDependOnOrder) {
    // Values over 12 orders of magnitude: a double sum depends on the order, the film's does not.
    Pcg32 rng(7, 1);
    std::vector<float> v(1000);
    for (float& x : v) x = std::exp(rng.uniform() * 28.0f - 14.0f);
    Film forward(1, 1), backward(1, 1), halves(1, 1), second(1, 1);
    for (size_t i = 0; i < v.size(); ++i) forward.addSample(0, 0, vec3(v[i]));
    for (size_t i = v.size(); i-- > 0;) backward.addSample(0, 0, vec3(v[i]));
    for (size_t i = 0; i < v.size(); ++i) (i < 400 ? halves : second).addSample(0, 0, vec3(v[i]));
    halves.add(second);
    EXPECT_EQ(forward.meanImage(), backward.meanImage());
    EXPECT_EQ(forward.meanImage(), halves.meanImage());
    EXPECT_EQ(halves.sampleCount(0, 0), 1000u);
    // The mean is the exact mean to the fixed-point resolution (2^-48 per sample).
    double exact = 0;
    for (float x : v) exact += double(x);
    EXPECT_NEAR(forward.pixel(0, 0).x, exact / v.size(), 1e-6 * exact / v.size());
    EXPECT_THROW(forward.add(Film(2, 1)), Error);
}

TEST(FilmShard, ThreeShardsMergeToTheUnsplitRenderBitForBit) {
    const Scene scene(furnaceScene(0.6f, 16, 12));
    RenderOptions opt;
    opt.seed = 4;
    opt.spp = 12;
    opt.sceneHash = "test";
    Film full(16, 16);
    Renderer(scene, opt).render(full);

    // Given out of order: the merge sorts by range.
    const std::vector<std::string> paths = {renderShard(scene, opt, 7, 12, "c"), renderShard(scene, opt, 0, 3, "a"),
                                            renderShard(scene, opt, 3, 7, "b")};
    std::vector<FilmShard> shards;
    for (const std::string& p : paths) shards.push_back(readFilmShard(p));
    EXPECT_EQ(shards[0].begin, 7);
    EXPECT_EQ(shards[0].end, 12);
    const MergedFilm m = mergeFilmShards(std::move(shards), 12);
    EXPECT_EQ(m.spp, 12);
    EXPECT_EQ(m.film.minSampleCount(), 12u);
    EXPECT_EQ(m.film.meanImage(), full.meanImage());
    // A shard alone is a different (noisier) image: the comparison can fail.
    EXPECT_NE(readFilmShard(paths[1]).film.meanImage(), full.meanImage());
    for (const std::string& p : paths) std::remove(p.c_str());
}

TEST(FilmShard, MergeRefusesShardsThatDoNotFormOneRender) {
    const Scene scene(furnaceScene(0.6f, 8, 6));
    RenderOptions opt;
    opt.seed = 4;
    opt.sceneHash = "test";
    const std::string a = renderShard(scene, opt, 0, 3, "ra"), b = renderShard(scene, opt, 3, 6, "rb"),
                      overlap = renderShard(scene, opt, 2, 6, "rover");
    RenderOptions otherSeed = opt;
    otherSeed.seed = 5;
    const std::string seed5 = renderShard(scene, otherSeed, 3, 6, "rseed");
    RenderOptions otherScene = opt;
    otherScene.sceneHash = "edited";
    const std::string edited = renderShard(scene, otherScene, 3, 6, "rscene");
    auto merge = [](std::vector<std::string> paths, int64_t spp) {
        std::vector<FilmShard> s;
        for (const std::string& p : paths) s.push_back(readFilmShard(p));
        return mergeFilmShards(std::move(s), spp);
    };
    EXPECT_NO_THROW(merge({a, b}, 6));
    EXPECT_NE(messageOf([&] { merge({a, overlap}, 6); }).find("overlap"), std::string::npos);
    EXPECT_NE(messageOf([&] { merge({b}, 6); }).find("samples 0:3 are missing"), std::string::npos);
    EXPECT_NE(messageOf([&] { merge({a, b}, 9); }).find("samples 6:9 are missing"), std::string::npos);
    const std::string seedMsg = messageOf([&] { merge({a, seed5}, 6); });
    EXPECT_NE(seedMsg.find(seed5 + ": different scene or settings"), std::string::npos) << seedMsg;
    EXPECT_NE(messageOf([&] { merge({a, edited}, 6); }).find("different scene or settings"), std::string::npos);

    // An interrupted shard (cancelled before its first pass) is refused as incomplete.
    RenderOptions cut = opt;
    cut.firstSample = 3;
    cut.spp = 3;
    cut.checkpointPath = tempState("rcut");
    Film film(8, 8);
    std::atomic<bool> cancel{true};
    Renderer(scene, cut).render(film, &cancel);
    const std::string cutMsg = messageOf([&] { merge({a, cut.checkpointPath}, 6); });
    EXPECT_NE(cutMsg.find("holds 0 of its 3 samples"), std::string::npos) << cutMsg;
    // ... and resuming it completes it: the merge then equals the unsplit render.
    cut.resume = true;
    Film resumed(8, 8);
    const Renderer r(scene, cut);
    resumed.load(cut.checkpointPath, r.settingsKey());
    r.render(resumed);
    RenderOptions whole = opt;
    whole.spp = 6;
    Film full(8, 8);
    Renderer(scene, whole).render(full);
    EXPECT_EQ(merge({a, cut.checkpointPath}, 6).film.meanImage(), full.meanImage());
    for (const std::string& p : {a, b, overlap, seed5, edited, cut.checkpointPath}) std::remove(p.c_str());
}

TEST(FilmShard, SettingsFieldReadsKeyFields) {
    EXPECT_EQ(settingsField("scene=a.xml;mode=rgb;n=3", "mode"), "rgb");
    EXPECT_EQ(settingsField("scene=a.xml;mode=rgb;n=3", "scene"), "a.xml");
    EXPECT_EQ(settingsField("scene=a.xml;mode=rgb;n=3", "n"), "3");
    EXPECT_EQ(settingsField("scene=a.xml;mode=rgb", "seed"), "");
}

TEST(FilmShard, OlderCheckpointFormatIsNamed) {
    const std::string path = tempState("v2");
    {
        std::ofstream f(path, std::ios::binary);
        f << "IRISCKP2" << std::string(64, '\0');
    }
    const std::string msg = messageOf([&] { readFilmShard(path); });
    EXPECT_NE(msg.find(path + ": checkpoint format version 2; this iris reads version 4"), std::string::npos) << msg;
    std::remove(path.c_str());
}

TEST(FilmShard, FixedPointConversionIsBoundedAndExactOnItsGrid) {
    EXPECT_EQ(Film::toFixed(1.0f), Film::FixedSum(1) << 48);
    EXPECT_EQ(Film::toFixed(-0.5f), -(Film::FixedSum(1) << 47));
    EXPECT_EQ(Film::toFixed(std::numeric_limits<float>::infinity()), Film::FixedSum(1) << 95);  // clamped to 2^47
    EXPECT_EQ(Film::toFixed(std::numeric_limits<float>::quiet_NaN()), 0);
    EXPECT_EQ(Film::toFixed(0x1p-50f), 0);  // below half the resolution 2^-48: rounds to 0
    EXPECT_EQ(Film::toFixed(0x1p-48f), 1);
}
