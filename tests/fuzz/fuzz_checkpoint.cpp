// libFuzzer target: render checkpoints (Film::save's format) through Film::load, for a 4x3 film
// and the header "fuzz" (the seeds are checkpoints written by save with that header).
#include "render/film.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string path = iris::fuzz::writeInput(data, size, "fuzz.ckpt");
    iris::fuzz::expectResultOrIrisError([&] {
        iris::Film film(4, 3);
        film.load(path, "fuzz");
    });
    return 0;
}
