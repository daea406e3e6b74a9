#include "render/pipelined_passes.h"

#include <atomic>
#include <memory>
#include <thread>

#include <tbb/task_arena.h>
#include <tbb/task_group.h>

namespace iris {

uint64_t runPipelinedPasses(int nTiles, int firstPass, int endPass, const std::function<void(int tile, int pass)>& body,
                            const std::function<bool()>& stop) {
    if (nTiles <= 0 || endPass <= firstPass) return 0;
    const uint64_t total = uint64_t(endPass - firstPass) * uint64_t(nTiles);
    std::atomic<uint64_t> next{0}, finished{0};
    std::atomic<bool> aborted{false};
    // nextPass[t]: the pass tile t may render next (the one after its last finished pass).
    const std::unique_ptr<std::atomic<int>[]> nextPass(new std::atomic<int>[size_t(nTiles)]);
    for (int t = 0; t < nTiles; ++t) nextPass[t].store(firstPass, std::memory_order_relaxed);

    auto worker = [&] {
        while (!aborted.load(std::memory_order_relaxed) && !stop()) {
            const uint64_t i = next.fetch_add(1, std::memory_order_relaxed);
            if (i >= total) return;
            const int pass = firstPass + int(i / uint64_t(nTiles)), tile = int(i % uint64_t(nTiles));
            // (pass − 1, tile) was handed out before this item, so a running thread holds it.
            while (nextPass[tile].load(std::memory_order_acquire) != pass) {
                if (aborted.load(std::memory_order_relaxed)) return;
                std::this_thread::yield();
            }
            try {
                // Isolated: a nested parallel wait inside the body (a lazily built table) must not
                // pick up another worker of this loop, which could wait for this very item.
                tbb::this_task_arena::isolate([&] { body(tile, pass); });
            } catch (...) {
                aborted = true;
                throw;
            }
            nextPass[tile].store(pass + 1, std::memory_order_release);
            finished.fetch_add(1, std::memory_order_relaxed);
        }
    };
    const int workers = tbb::this_task_arena::max_concurrency();
    tbb::task_group group;
    for (int k = 1; k < workers; ++k) group.run(worker);
    try {
        worker();  // the calling thread is one of the workers
    } catch (...) {
        aborted = true;
        group.wait();  // the others return at their next item; the first exception is this one
        throw;
    }
    group.wait();
    return finished.load();
}

}  // namespace iris
