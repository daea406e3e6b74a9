// Image file I/O: EXR output through OpenEXR (so metadata is exactly what we put in the header),
// LDR output and all input through OpenImageIO. Every failure becomes an iris::Error "path: reason".
#include "core/image.h"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <system_error>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <OpenImageIO/imageio.h>

#include "core/error.h"

namespace iris {

namespace {

constexpr size_t kMaxPixels = size_t(1) << 28;

std::string tempPathFor(const std::string& path) { return strCat(path, ".tmp-", ::getpid()); }

/// Rename the finished temporary file over `path` (atomic on POSIX within one file system).
void commitTemp(const std::string& tmp, const std::string& path) {
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec) {
        std::filesystem::remove(tmp, ec);
        fail(path, ": cannot move the written file into place: ", ec.message());
    }
}

void removeQuietly(const std::string& p) {
    std::error_code ec;
    std::filesystem::remove(p, ec);
}

void checkWritable(const std::string& path, const Image& img) {
    if (img.width <= 0 || img.height <= 0 || img.channels <= 0)
        fail(path, ": cannot write an empty image (", img.width, "x", img.height, "x", img.channels, ")");
    if (img.pixels.size() != img.pixelCount() * size_t(img.channels))
        fail(path, ": image has ", img.pixels.size(), " values, expected ", img.pixelCount() * size_t(img.channels));
}

}  // namespace

std::vector<std::string> defaultChannelNames(int channels) {
    if (channels == 1) return {"Y"};
    if (channels == 3) return {"R", "G", "B"};
    if (channels == 4) return {"R", "G", "B", "A"};
    std::vector<std::string> names;
    for (int c = 0; c < channels; ++c) names.push_back(strCat("C", c));
    return names;
}

Image::Image(int w, int h, int c)
    : width(w), height(h), channels(c), pixels(size_t(std::max(w, 0)) * size_t(std::max(h, 0)) * size_t(std::max(c, 0)), 0.0f),
      channelNames(defaultChannelNames(c)) {}

int Image::channelIndex(const std::string& name) const {
    for (size_t i = 0; i < channelNames.size(); ++i)
        if (channelNames[i] == name) return int(i);
    return -1;
}

std::string metadataValue(const ImageMetadata& meta, const std::string& key, const std::string& def) {
    for (const auto& [k, v] : meta)
        if (k == key) return v;
    return def;
}

void writeEXR(const std::string& path, const Image& img, const ImageMetadata& meta) {
    checkWritable(path, img);
    std::vector<std::string> names = img.channelNames;
    if (names.size() != size_t(img.channels)) names = defaultChannelNames(img.channels);
    for (size_t i = 0; i < names.size(); ++i)
        for (size_t j = i + 1; j < names.size(); ++j)
            if (names[i] == names[j]) fail(path, ": duplicate channel name '", names[i], "'");

    const std::string tmp = tempPathFor(path);
    try {
        Imf::Header header(img.width, img.height);
        header.compression() = Imf::ZIP_COMPRESSION;
        for (const auto& [key, value] : meta) header.insert(key, Imf::StringAttribute(value));
        Imf::FrameBuffer fb;
        const size_t xStride = sizeof(float) * size_t(img.channels);
        const size_t yStride = xStride * size_t(img.width);
        for (int c = 0; c < img.channels; ++c) {
            header.channels().insert(names[c], Imf::Channel(Imf::FLOAT));
            // const_cast: OpenEXR's Slice takes char* for both reading and writing; we only write.
            char* base = reinterpret_cast<char*>(const_cast<float*>(img.pixels.data() + c));
            fb.insert(names[c], Imf::Slice(Imf::FLOAT, base, xStride, yStride));
        }
        {
            Imf::OutputFile file(tmp.c_str(), header);
            file.setFrameBuffer(fb);
            file.writePixels(img.height);
        }
    } catch (const Error&) {
        removeQuietly(tmp);
        throw;
    } catch (const std::exception& e) {
        removeQuietly(tmp);
        fail(path, ": cannot write EXR: ", e.what());
    }
    commitTemp(tmp, path);
}

void writeLDR(const std::string& path, const Image& img) {
    checkWritable(path, img);
    const std::string tmp = tempPathFor(path);
    // The plugin is chosen from the real path's extension; the data then goes to the temp file.
    auto out = OIIO::ImageOutput::create(path);
    if (!out) fail(path, ": cannot write this image format: ", OIIO::geterror());
    std::string ext = std::filesystem::path(path).extension().string();
    for (char& ch : ext) ch = char(std::tolower(static_cast<unsigned char>(ch)));
    const bool noAlpha = ext == ".jpg" || ext == ".jpeg";  // JPEG has no alpha channel
    const int channels = std::min(img.channels, noAlpha ? 3 : 4);
    OIIO::ImageSpec spec(img.width, img.height, channels, OIIO::TypeDesc::UINT8);
    std::vector<unsigned char> bytes(img.pixelCount() * size_t(channels));
    for (size_t p = 0; p < img.pixelCount(); ++p)
        for (int c = 0; c < channels; ++c) {
            float v = img.pixels[p * size_t(img.channels) + size_t(c)];
            if (!(v > 0.0f)) v = 0.0f;  // also maps NaN to 0
            bytes[p * size_t(channels) + size_t(c)] = (unsigned char)std::lround(std::min(v, 1.0f) * 255.0f);
        }
    if (!out->open(tmp, spec)) {
        const std::string err = out->geterror();
        removeQuietly(tmp);
        fail(path, ": cannot open for writing: ", err);
    }
    const bool ok = out->write_image(OIIO::TypeDesc::UINT8, bytes.data());
    const std::string err = ok ? std::string() : out->geterror();
    const bool closed = out->close();
    if (!ok || !closed) {
        removeQuietly(tmp);
        fail(path, ": cannot write image: ", ok ? out->geterror() : err);
    }
    commitTemp(tmp, path);
}

Image readImage(const std::string& path) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) fail(path, ": file not found");
    if (std::filesystem::is_directory(path, ec)) fail(path, ": is a directory, not an image");
    auto in = OIIO::ImageInput::open(path);
    if (!in) {
        std::string err = OIIO::geterror();
        if (err.empty()) err = "not a readable image";
        fail(path, ": cannot read image: ", err);
    }
    const OIIO::ImageSpec& spec = in->spec();
    if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0 || spec.depth > 1)
        fail(path, ": unsupported image size ", spec.width, "x", spec.height, "x", spec.nchannels);
    if (size_t(spec.width) * size_t(spec.height) > kMaxPixels)
        fail(path, ": image of ", spec.width, "x", spec.height, " pixels exceeds the limit of 2^28 pixels");
    if (spec.nchannels > 1024) fail(path, ": absurd channel count ", spec.nchannels);

    Image img;
    img.width = spec.width;
    img.height = spec.height;
    img.channels = spec.nchannels;
    img.channelNames.clear();
    for (int c = 0; c < spec.nchannels; ++c)
        img.channelNames.push_back(c < int(spec.channelnames.size()) ? spec.channelnames[c] : strCat("C", c));
    img.pixels.assign(img.pixelCount() * size_t(img.channels), 0.0f);
    const bool ok = in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, img.pixels.data());
    if (!ok || in->has_error()) {
        std::string err = in->geterror();
        if (err.empty()) err = "corrupt or truncated pixel data";
        in->close();
        fail(path, ": cannot read pixels: ", err);
    }
    in->close();
    return img;
}

ImageMetadata readEXRMetadata(const std::string& path) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) fail(path, ": file not found");
    ImageMetadata meta;
    try {
        Imf::InputFile file(path.c_str());
        const Imf::Header& header = file.header();
        for (auto it = header.begin(); it != header.end(); ++it) {
            if (const auto* s = dynamic_cast<const Imf::StringAttribute*>(&it.attribute()))
                meta.emplace_back(it.name(), s->value());
        }
    } catch (const std::exception& e) {
        fail(path, ": cannot read EXR header: ", e.what());
    }
    return meta;
}

}  // namespace iris
