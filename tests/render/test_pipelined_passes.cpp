// The render loop's barrier-free passes (render/pipelined_passes.h): every (pass, tile) item runs
// once, each tile's passes run in order and never two at a time, stopping and errors end the loop
// without waiting for the rest, for 1, 2 and 4 threads (also under ThreadSanitizer: TSan.*).
#include <atomic>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "render/pipelined_passes.h"

using namespace iris;

namespace {

/// The passes each tile ran, in the order it ran them, and whether two ever overlapped.
struct TileLog {
    std::vector<std::vector<int>> passes;
    std::vector<std::atomic<int>> busy;
    std::atomic<bool> overlapped{false};
    explicit TileLog(int nTiles) : passes(size_t(nTiles)), busy(size_t(nTiles)) {}
    void record(int tile, int pass) {
        if (busy[tile].fetch_add(1) != 0) overlapped = true;
        passes[tile].push_back(pass);
        busy[tile].fetch_sub(1);
    }
};

/// True if every tile ran exactly the passes [first, end) in increasing order.
bool inOrder(const std::vector<std::vector<int>>& passes, int first, int end) {
    for (const std::vector<int>& p : passes) {
        if (int(p.size()) != end - first) return false;
        for (int i = 0; i < int(p.size()); ++i)
            if (p[size_t(i)] != first + i) return false;
    }
    return true;
}

const auto kNever = [] { return false; };

}  // namespace

TEST(PipelinedPasses, EveryItemOnceAndEachTileInPassOrder) {
    for (int threads : {1, 2, 4})
        for (int nTiles : {1, 3, 37}) {
            tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
            TileLog log(nTiles);
            const uint64_t done = runPipelinedPasses(nTiles, 5, 45, [&](int t, int p) { log.record(t, p); }, kNever);
            EXPECT_EQ(done, uint64_t(40 * nTiles)) << threads << " threads, " << nTiles << " tiles";
            EXPECT_TRUE(inOrder(log.passes, 5, 45)) << threads << " threads, " << nTiles << " tiles";
            EXPECT_FALSE(log.overlapped) << threads << " threads, " << nTiles << " tiles";
        }
}

TEST(PipelinedPasses, TheOrderCheckRejectsAWrongLog) {
    EXPECT_TRUE(inOrder({{0, 1, 2}, {0, 1, 2}}, 0, 3));
    EXPECT_FALSE(inOrder({{0, 2, 1}, {0, 1, 2}}, 0, 3));  // passes swapped
    EXPECT_FALSE(inOrder({{0, 1, 2}, {0, 1}}, 0, 3));     // a pass missing
    EXPECT_FALSE(inOrder({{0, 1, 1, 2}}, 0, 3));          // a pass twice
}

TEST(PipelinedPasses, StopEndsTheLoopAtAnItemBoundary) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    std::atomic<int> ran{0};
    const uint64_t done = runPipelinedPasses(4, 0, 1000, [&](int, int) { ++ran; }, [&] { return ran.load() >= 6; });
    EXPECT_EQ(done, 6u);  // one thread: the items before the stop, none after
    EXPECT_EQ(ran.load(), 6);

    tbb::global_control two(tbb::global_control::max_allowed_parallelism, 2);
    ran = 0;
    const uint64_t done2 = runPipelinedPasses(4, 0, 1000, [&](int, int) { ++ran; }, [&] { return ran.load() >= 6; });
    EXPECT_GE(done2, 6u);  // a second thread may finish the item it had started
    EXPECT_LE(done2, 7u);
    EXPECT_EQ(runPipelinedPasses(4, 3, 3, [&](int, int) { ++ran; }, kNever), 0u);  // no passes: nothing runs
}

TEST(PipelinedPasses, AnErrorInOneItemEndsTheLoopAndIsRethrown) {
    for (int threads : {1, 2}) {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
        std::atomic<int> after{0};
        // One tile: a second thread waits for the failing item's tile and must give up, not hang.
        EXPECT_THROW(runPipelinedPasses(1, 0, 100, [&](int, int p) {
            if (p == 3) throw std::runtime_error("item failed");
            if (p > 3) ++after;
        }, kNever), std::runtime_error);
        EXPECT_EQ(after.load(), 0) << threads << " threads";
    }
}
