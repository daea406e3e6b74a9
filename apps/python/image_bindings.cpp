// EXR files from Python: write(path, pixels (H, W, C) float32, metadata, channel names) and read
// → (pixels, metadata, channel names), through core/io/image.h (the renderer's own reader/writer).
#include <filesystem>

#include "apps/python/bindings.h"
#include "core/io/image.h"

namespace iris::python {

namespace {

void write(const std::string& path, const py::array& pixels, const ImageMetadata& meta,
           const std::vector<std::string>& channelNames) {
    py::array_t<float, py::array::c_style | py::array::forcecast> a;
    if (pixels.ndim() == 2) {
        a = inputArray<float>(py::array(pixels).reshape({pixels.shape(0), pixels.shape(1), py::ssize_t(1)}), "image", 3);
    } else {
        a = inputArray<float>(pixels, "image", 3);
    }
    if (a.shape(0) < 1 || a.shape(1) < 1 || a.shape(2) < 1) fail("image: every dimension must be at least 1, got shape (", a.shape(0), ", ", a.shape(1), ", ", a.shape(2), ")");
    Image img(int(a.shape(1)), int(a.shape(0)), int(a.shape(2)));
    std::copy(a.data(), a.data() + a.size(), img.pixels.begin());
    if (!channelNames.empty()) {
        if (channelNames.size() != size_t(img.channels))
            fail("channels: ", channelNames.size(), " names given for an image of ", img.channels, " channels");
        img.channelNames = channelNames;
    }
    writeEXR(path, img, meta);
}

py::tuple read(const std::string& path) {
    Image img = readImage(path);
    // Header attributes exist in EXR files only (other formats are read through OpenImageIO).
    const bool exr = std::filesystem::path(path).extension() == ".exr";
    const ImageMetadata meta = exr ? readEXRMetadata(path) : ImageMetadata{};
    py::dict d;
    for (const auto& [k, v] : meta) d[py::str(k)] = v;
    const std::vector<std::string> names = img.channelNames;
    auto arr = ownedArray(std::move(img.pixels), {img.height, img.width, img.channels});
    return py::make_tuple(arr, d, names);
}

}  // namespace

void bindImages(py::module_& m) {
    m.def("write_exr", &write, py::arg("path"), py::arg("image"), py::arg("metadata"), py::arg("channels"));
    m.def("read_exr", &read, py::arg("path"));
}

}  // namespace iris::python
