// Tells ThreadSanitizer about the fork-join order of a parallel loop. Debian's TBB library is not
// instrumented, so TSan does not see that everything before tbb::parallel_for happens before each
// loop body and each body before the code after the loop (TBB's documented guarantee), and
// reports the film writes of successive passes as races. A ForkJoin object states exactly that
// order with TSan's __tsan_release/__tsan_acquire annotations (the ThreadSanitizer manual,
// "dynamic annotations"); in builds without TSan it compiles to nothing.
#pragma once

#if defined(__SANITIZE_THREAD__)
#define IRIS_TSAN_ANNOTATIONS 1
#elif defined(__has_feature)
#if __has_feature(thread_sanitizer)
#define IRIS_TSAN_ANNOTATIONS 1
#endif
#endif

#ifdef IRIS_TSAN_ANNOTATIONS
extern "C" void __tsan_acquire(void* addr);
extern "C" void __tsan_release(void* addr);
#endif

namespace iris {

class ForkJoin {
public:
    /// Before the loop: what the launching thread did so far happens before every body.
    void fork() { release(&forked_); }
    /// After the loop: every body happens before what the launching thread does next.
    void join() { acquire(&joined_); }

    /// Held by one loop body for its duration (also across early returns).
    class Body {
    public:
        explicit Body(ForkJoin& fj) : fj_(fj) { fj_.acquire(&fj_.forked_); }
        ~Body() { fj_.release(&fj_.joined_); }
        Body(const Body&) = delete;
        Body& operator=(const Body&) = delete;

    private:
        ForkJoin& fj_;
    };

private:
    // Two tokens, so that bodies are not ordered among themselves (one body's release is never
    // another body's acquire): a race between two bodies is still reported.
#ifdef IRIS_TSAN_ANNOTATIONS
    static void acquire(char* token) { __tsan_acquire(token); }
    static void release(char* token) { __tsan_release(token); }
#else
    static void acquire(char*) {}
    static void release(char*) {}
#endif
    char forked_ = 0, joined_ = 0;
};

}  // namespace iris
