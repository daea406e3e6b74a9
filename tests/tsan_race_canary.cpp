// A deliberate data race inside a tbb::parallel_for body, stated in the same fork-join way as
// the renderer (core/tsan_fork_join.h). Under IRIS_TSAN, CTest expects it to FAIL
// (TSan.DetectsARaceInALoopBody): proof that tests/tsan.supp and the annotations do not hide a
// race in iris's own loop bodies.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cstdio>

#include "core/tsan_fork_join.h"

int main() {
    long shared = 0;  // written by every body without synchronisation: a race
    iris::ForkJoin forkJoin;
    forkJoin.fork();
    tbb::parallel_for(tbb::blocked_range<int>(0, 64, 1), [&](const tbb::blocked_range<int>& r) {
        // The bodies stay unordered among themselves, also when they run one after the other.
        const iris::ForkJoin::Body body(forkJoin);
        for (int i = r.begin(); i != r.end(); ++i) shared += i;
    });
    forkJoin.join();
    std::printf("%ld\n", shared);
    return 0;
}
