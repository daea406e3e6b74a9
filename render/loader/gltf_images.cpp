#include "render/loader/gltf_images.h"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <initializer_list>
#include <fstream>

#include "core/io/image.h"
#include "core/io/output_file.h"
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

/// The file extension of an encoded image from its signature (PNG: 89 'PNG' 0D 0A 1A 0A, PNG
/// specification §5.2; JPEG: FF D8 FF, ITU T.81 SOI marker; WebP: "RIFF" .... "WEBP", RFC 9649),
/// the formats glTF and its texture extensions name; "" for anything else.
std::string extensionOf(const std::vector<unsigned char>& b) {
    auto starts = [&](std::initializer_list<unsigned char> sig, size_t at = 0) {
        if (b.size() < at + sig.size()) return false;
        return std::equal(sig.begin(), sig.end(), b.begin() + std::ptrdiff_t(at));
    };
    if (starts({0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A})) return ".png";
    if (starts({0xFF, 0xD8, 0xFF})) return ".jpg";
    if (starts({'R', 'I', 'F', 'F'}) && starts({'W', 'E', 'B', 'P'}, 8)) return ".webp";
    return "";
}

/// core's readImage reads files: the bytes go to a private temporary file, removed afterwards. The
/// file gets its format's extension, so that OpenImageIO opens it with that format's reader
/// instead of trying every reader on a name without one.
Image readEncoded(const std::vector<unsigned char>& bytes, const std::string& what) {
    const std::string ext = extensionOf(bytes);
    std::string tmpl = (std::filesystem::path(temporaryFolder()) / ("iris-gltf-image-XXXXXX" + ext)).string();
    const int fd = mkstemps(tmpl.data(), int(ext.size()));
    if (fd < 0) fail(what, ": cannot create a temporary file in '", temporaryFolder(), "' ($TMPDIR) to decode the image: ", std::strerror(errno));
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
