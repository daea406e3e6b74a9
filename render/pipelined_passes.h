// The render loop's passes without a barrier between them. A pass renders one sample per pixel
// over every tile; with a barrier, a thread that finishes its share of pass p waits for the slowest
// tile (and TBB's workers go to sleep and wake up again) before pass p + 1 starts, which on a
// small image costs a visible part of the 2-thread speed-up (docs/performance.md, scaling).
// Here the items (pass, tile) are handed out in pass-major order from one counter, and an item
// (p, t) starts only after (p − 1, t) has finished: each tile's passes still run in order, so each
// pixel is accumulated in sample order and images stay bit-identical for any thread count.
#pragma once

#include <cstdint>
#include <functional>

namespace iris {

/// Runs body(tile, pass) for pass in [firstPass, endPass) and tile in [0, nTiles) on TBB's
/// threads (at most the current tbb::global_control parallelism), (p, t) after (p − 1, t).
/// `stop()` is asked before each item: once it is true no further item starts (items already
/// started finish). An exception from a body stops the others and is rethrown. Returns the number
/// of items finished.
uint64_t runPipelinedPasses(int nTiles, int firstPass, int endPass, const std::function<void(int tile, int pass)>& body,
                            const std::function<bool()>& stop);

}  // namespace iris
