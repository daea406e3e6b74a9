// libFuzzer target: Mitsuba `.vol` grid volumes (core/io/vol_reader.h) through parseVol.
#include "core/io/vol_reader.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string bytes(reinterpret_cast<const char*>(data), size);
    iris::fuzz::expectResultOrIrisError([&] { iris::parseVol(bytes, "fuzz.vol"); });
    return 0;
}
