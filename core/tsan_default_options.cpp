// ThreadSanitizer's default options for every iris executable of an IRIS_TSAN build (the
// runtime calls __tsan_default_options at start-up; TSAN_OPTIONS still overrides): stop at the
// first report and read the third-party suppressions of tests/tsan.supp (docs/testing.md,
// "Sanitizers"). Compiled to nothing in other builds.
#if defined(IRIS_TSAN_SUPPRESSIONS)
extern "C" const char* __tsan_default_options() {
    return "halt_on_error=1:second_deadlock_stack=1:suppressions=" IRIS_TSAN_SUPPRESSIONS;
}
#endif
