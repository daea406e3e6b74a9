#include "render/loader/gltf_images.h"

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "core/io/image.h"
#include "core/xml/xml_values.h"
#include "core/srgb_transfer.h"

namespace iris::gltf {

namespace {

/// The image's encoded bytes: tinygltf keeps them as they are (gltf_document.cpp), from the URI,
/// the data URI or the buffer view.
const std::vector<unsigned char>& encodedBytes(const Document& doc, int index, const std::string& path) {
    const tinygltf::Image& img = doc.model.images[size_t(index)];
    if (img.image.empty() && !img.uri.empty() && img.uri.rfind("data:", 0) != 0)
        failAtPath(doc, path, "cannot read the image file '", img.uri, "' (relative to '", doc.dir, "')");
    if (img.image.empty()) failAtPath(doc, path, "the image has no data (bufferView ", img.bufferView, ")");
    return img.image;
}

/// core's readImage reads files: the bytes go to a private temporary file, removed afterwards.
Image readEncoded(const std::vector<unsigned char>& bytes, const std::string& what) {
    std::string tmpl = (std::filesystem::temp_directory_path() / "iris-gltf-image-XXXXXX").string();
    const int fd = mkstemp(tmpl.data());
    if (fd < 0) fail(what, ": cannot create a temporary file to decode the image");
    close(fd);
    struct Remove {
        std::string p;
        ~Remove() { std::remove(p.c_str()); }
    } remove{tmpl};
    {
        std::ofstream out(tmpl, std::ios::binary);
        out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
        if (!out) fail(what, ": cannot write the image to a temporary file");
    }
    try {
        return readImage(tmpl);
    } catch (const Error& e) {
        std::string msg = e.what();
        if (msg.rfind(tmpl, 0) == 0) msg = msg.substr(tmpl.size());  // the temporary name means nothing to the user
        fail(what, ": cannot decode the image", msg);
    }
}

}  // namespace

std::shared_ptr<const Bitmap> decodeImage(const Document& doc, int index, bool srgb, const std::string& path) {
    Image img = readEncoded(encodedBytes(doc, index, path), strCat(doc.path, ": ", path));
    if (srgb) {
        const int colour = std::min(img.channels, img.channels == 2 || img.channels == 4 ? img.channels - 1 : img.channels);
        for (size_t p = 0; p < img.pixelCount(); ++p)
            for (int c = 0; c < colour; ++c) img.pixels[p * size_t(img.channels) + size_t(c)] = srgbToLinear(img.pixels[p * size_t(img.channels) + size_t(c)]);
    }
    return std::make_shared<const Bitmap>(std::move(img));
}

}  // namespace iris::gltf
