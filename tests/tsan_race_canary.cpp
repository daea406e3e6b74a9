// A deliberate data race between two tbb::parallel_for bodies, stated in the same fork-join way
// as the renderer (core/tsan_fork_join.h). Under IRIS_TSAN, CTest expects it to FAIL
// (TSan.DetectsARaceInALoopBody): proof that tests/tsan.supp and the annotations do not hide a
// race in iris's own loop bodies.
//
// TSan reports a race only between accesses made by two threads with no happens-before between
// them; bodies that one thread runs one after the other are ordered by that thread's program
// order. So the loop has two bodies and the first to start waits until the other has started on
// another thread before it returns. The hand-shake uses relaxed atomics, which order nothing for
// TSan, so both bodies' writes to `shared` stay unordered. If no second thread joins within the
// wait (a machine that runs TBB on one thread), the canary says so and exits 0: the expected
// failure is then missing and CTest marks the test failed, which is what it should say.
#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <thread>

#include "core/tsan_fork_join.h"

int main() {
    // Two workers, also on a machine whose default would be one.
    const tbb::global_control twoThreads(tbb::global_control::max_allowed_parallelism, 2);
    long shared = 0;  // written by both bodies without synchronisation: a race
    std::atomic<int> started{0};
    std::atomic<bool> sawTwoThreads{false};
    const auto giveUp = std::chrono::steady_clock::now() + std::chrono::seconds(30);
    iris::ForkJoin forkJoin;
    forkJoin.fork();
    tbb::parallel_for(
        tbb::blocked_range<int>(0, 2, 1),
        [&](const tbb::blocked_range<int>& r) {
            const iris::ForkJoin::Body body(forkJoin);
            for (int i = r.begin(); i != r.end(); ++i) shared += i + 1;
            if (started.fetch_add(1, std::memory_order_relaxed) == 1) return;  // the second body
            // The first body: wait while this thread is busy, so the second must start on another.
            while (started.load(std::memory_order_relaxed) < 2 && std::chrono::steady_clock::now() < giveUp)
                std::this_thread::yield();
            sawTwoThreads.store(started.load(std::memory_order_relaxed) == 2, std::memory_order_relaxed);
        },
        tbb::simple_partitioner());
    forkJoin.join();
    if (!sawTwoThreads.load(std::memory_order_relaxed)) {
        std::printf("tsan_race_canary: the two loop bodies did not run on two threads within 30 s; no race was made\n");
        return 0;
    }
    std::printf("%ld\n", shared);
    return 0;
}
