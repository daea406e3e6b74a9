// libFuzzer target: texture and environment-map input through readImage: files with the OpenEXR
// magic number go through OpenEXR, all others (PNG, JPEG, HDR, ...) through the OpenImageIO module.
// The EXR metadata reader (used by compare and merge) gets the same bytes, and an image with
// spectral channels (render --spectral-output, Fichet et al. 2021) goes on through the spectral
// channel parser and the colour derived from its bins (what compare does with it).
#include "core/io/image.h"
#include "core/io/spectral_layout.h"
#include "spectral/spectral_bins.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string path = iris::fuzz::writeInput(data, size, "fuzz.img");
    iris::fuzz::expectResultOrIrisError([&] {
        const iris::Image img = iris::readImage(path);
        if (iris::hasSpectralChannels(img)) iris::xyzImage(iris::spectralChannels(img, path));
    });
    iris::fuzz::expectResultOrIrisError([&] { iris::readEXRMetadata(path); });
    return 0;
}
