// libFuzzer target: texture and environment-map input through readImage: files with the OpenEXR
// magic number go through OpenEXR, all others (PNG, JPEG, HDR, ...) through the OpenImageIO module.
// The EXR metadata reader (used by compare and merge) gets the same bytes.
#include "core/io/image.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string path = iris::fuzz::writeInput(data, size, "fuzz.img");
    iris::fuzz::expectResultOrIrisError([&] { iris::readImage(path); });
    iris::fuzz::expectResultOrIrisError([&] { iris::readEXRMetadata(path); });
    return 0;
}
