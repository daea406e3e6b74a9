#include "render/pipelined_passes.h"

#include <atomic>
#include <exception>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include <tbb/global_control.h>

namespace iris {

uint64_t runPipelinedPasses(int nTiles, int firstPass, int endPass, const std::function<void(int tile, int pass)>& body,
                            const std::function<bool()>& stop) {
    if (nTiles <= 0 || endPass <= firstPass) return 0;
    const uint64_t total = uint64_t(endPass - firstPass) * uint64_t(nTiles);
    std::atomic<uint64_t> next{0}, finished{0};
    std::atomic<bool> aborted{false};
    std::exception_ptr error;
    std::mutex errorMutex;
    // nextPass[t]: the pass tile t may render next (the one after its last finished pass).
    const std::unique_ptr<std::atomic<int>[]> nextPass(new std::atomic<int>[size_t(nTiles)]);
    for (int t = 0; t < nTiles; ++t) nextPass[t].store(firstPass, std::memory_order_relaxed);

    auto work = [&] {
        while (!aborted.load(std::memory_order_relaxed) && !stop()) {
            const uint64_t i = next.fetch_add(1, std::memory_order_relaxed);
            if (i >= total) return;
            const int pass = firstPass + int(i / uint64_t(nTiles)), tile = int(i % uint64_t(nTiles));
            // (pass − 1, tile) was handed out before this item, so a running thread holds it.
            while (nextPass[tile].load(std::memory_order_acquire) != pass) {
                if (aborted.load(std::memory_order_relaxed)) return;
                std::this_thread::yield();
            }
            body(tile, pass);
            nextPass[tile].store(pass + 1, std::memory_order_release);
            finished.fetch_add(1, std::memory_order_relaxed);
        }
    };
    auto worker = [&] {
        try {
            work();
        } catch (...) {
            aborted = true;
            const std::lock_guard<std::mutex> lock(errorMutex);
            if (!error) error = std::current_exception();
        }
    };
    // Plain threads, as many as TBB may use (the renderer's --threads limit): the calling thread
    // and the others. Their start and join order everything for ThreadSanitizer, and a body's
    // own parallel work (a lazily built table) runs in TBB's pool without waiting on this loop.
    const size_t threads = tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism);
    std::vector<std::thread> others;
    for (size_t k = 1; k < threads; ++k) others.emplace_back(worker);
    worker();
    for (std::thread& t : others) t.join();
    if (error) std::rethrow_exception(error);
    return finished.load();
}

}  // namespace iris
