// The render loop's timeline (render/render_timeline.h) and the scaling model built on it: every
// tile of every pass is recorded once inside its pass, recording changes no pixel, and the two
// schedules (with and without the barrier after each pass) give the makespans worked out by hand.
#include <gtest/gtest.h>

#include <set>
#include <utility>

#include "render/film.h"
#include "render/render_timeline.h"
#include "render/renderer.h"
#include "render/scene.h"
#include "tests/support/render_test_scenes.h"

using namespace iris;

TEST(RenderTimeline, RecordsEveryTileOfEveryPassOnceAndChangesNoPixel) {
    const Scene scene(iris::testing::furnaceScene(0.5f, 40, 3));  // 40×40: 3×3 tiles of 16
    for (int threads : {1, 2}) {
        RenderOptions opt;
        opt.threads = threads;
        opt.seed = 3;
        Film plain(40, 40), timed(40, 40);
        Renderer(scene, opt).render(plain);
        RenderTimeline tl;
        opt.timeline = &tl;
        Renderer(scene, opt).render(timed);
        for (int y = 0; y < 40; ++y)
            for (int x = 0; x < 40; ++x) ASSERT_EQ(plain.pixel(x, y), timed.pixel(x, y)) << x << "," << y;
        ASSERT_EQ(tl.passes.size(), 3u);
        ASSERT_EQ(tl.tiles.size(), 27u);
        std::set<std::pair<int, int>> seen;
        for (const TileTiming& t : tl.tiles) {
            EXPECT_TRUE(seen.insert({t.pass, t.tile}).second) << "pass " << t.pass << " tile " << t.tile;
            ASSERT_GE(t.pass, 0);
            ASSERT_LT(t.pass, 3);
            EXPECT_LE(tl.passes[size_t(t.pass)].start, t.start);
            EXPECT_LE(t.start, t.end);
            EXPECT_LE(t.end, tl.passes[size_t(t.pass)].end);
            EXPECT_GE(t.worker, 0);
            EXPECT_LT(t.worker, threads);
        }
        for (size_t p = 1; p < tl.passes.size(); ++p) EXPECT_LE(tl.passes[p - 1].end, tl.passes[p].start);
        EXPECT_LE(tl.passes.back().end, tl.end);
        const TimelineSummary s = summarize(tl, threads);
        EXPECT_GT(s.work, 0.0);
        EXPECT_GE(s.outside, 0.0);
        EXPECT_NEAR(s.outside + (s.work + s.idle) / threads, s.total, 1e-9);  // the parts add up
    }
}

TEST(RenderTimeline, SchedulesMatchHandWorkedCases) {
    const auto passes = [](int n, std::vector<double> tiles, double overhead = 0) {
        return std::vector<PassWork>(size_t(n), PassWork{std::move(tiles), overhead});
    };
    // One worker: the sum of everything, overheads included.
    EXPECT_DOUBLE_EQ(scheduleWithBarrier(passes(2, {3, 1, 1, 1}, 0.5), 1), 13.0);
    EXPECT_DOUBLE_EQ(scheduleWithoutBarrier(passes(2, {3, 1, 1, 1}, 0.5), 1), 13.0);
    // Two workers, tiles 3,1,1,1: the long tile bounds each pass at 3.
    EXPECT_DOUBLE_EQ(scheduleWithBarrier(passes(2, {3, 1, 1, 1}), 2), 6.0);
    // Three unit tiles on two workers: the barrier idles one worker at each pass's end (2 per
    // pass); without it the second pass fills that gap: 0–1 a b, 1–2 c a', 2–3 b' c'.
    EXPECT_DOUBLE_EQ(scheduleWithBarrier(passes(2, {1, 1, 1}), 2), 4.0);
    EXPECT_DOUBLE_EQ(scheduleWithoutBarrier(passes(2, {1, 1, 1}), 2), 3.0);
    // A tile's passes stay in order: one tile on many workers takes one unit per pass (a schedule
    // that ignored the order would give 1).
    EXPECT_DOUBLE_EQ(scheduleWithoutBarrier(passes(3, {1}), 8), 3.0);
    EXPECT_DOUBLE_EQ(scheduleWithBarrier(passes(3, {1}), 8), 3.0);
}
