// libFuzzer target: Mitsuba .serialized meshes (zlib streams, versions 3 and 4): the shape count,
// then every shape the file claims to hold (at most 4, to bound the time per input).
#include "core/io/serialized_reader.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string path = iris::fuzz::writeInput(data, size, "fuzz.serialized");
    iris::fuzz::expectResultOrIrisError([&] {
        const int shapes = iris::serializedShapeCount(path);
        for (int i = 0; i < shapes && i < 4; ++i) iris::fuzz::expectResultOrIrisError([&] { iris::readSerialized(path, i); });
    });
    // An index the file does not have must be refused, never read.
    iris::fuzz::expectResultOrIrisError([&] { iris::readSerialized(path, -1); });
    return 0;
}
