// libFuzzer target: Stanford PLY meshes (ASCII, binary little and big endian) through parsePly.
#include "core/io/ply_reader.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    iris::fuzz::expectResultOrIrisError([&] { iris::parsePly(text, "fuzz.ply"); });
    return 0;
}
