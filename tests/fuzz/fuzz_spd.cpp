// libFuzzer target: ".spd" spectrum files (lines "lambda value", '#' comments) through loadSpdFile,
// as each kind of spectrum (the reflectance kind also checks the [0, 1] bound).
#include "spectral/spectrum_factory.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string path = iris::fuzz::writeInput(data, size, "fuzz.spd");
    for (iris::SpectrumKind kind : {iris::SpectrumKind::Reflectance, iris::SpectrumKind::Unbounded})
        iris::fuzz::expectResultOrIrisError([&] { iris::loadSpdFile(path, kind); });
    return 0;
}
