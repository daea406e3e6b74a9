// libFuzzer target: Wavefront OBJ meshes through parseObj.
#include "core/io/obj_reader.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    iris::fuzz::expectResultOrIrisError([&] { iris::parseObj(text, "fuzz.obj"); });
    return 0;
}
