// Image file I/O: EXR output and input through OpenEXR (so metadata is exactly what we put in the
// header); LDR output and non-EXR input through OpenImageIO, which lives in a module loaded on
// demand (core/io/oiio_loader.h). Every failure becomes an iris::Error "path: reason".
#include "core/io/image.h"

#include <strings.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
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
#include <OpenEXR/ImfPartType.h>
#include <OpenEXR/ImfTestFile.h>

#include "core/error.h"
#include "core/memory_budget.h"
#include "core/io/atomic_file.h"
#include "core/io/exr_header_check.h"
#include "core/input_file.h"
#include "core/io/oiio_loader.h"
#include "core/io/png_header_check.h"
#include "core/io/png_writer.h"
#include "core/io/webp_header_check.h"

namespace iris {

namespace {

constexpr size_t kMaxPixels = size_t(1) << 28;

void checkWritable(const std::string& path, const Image& img) {
    if (img.width <= 0 || img.height <= 0 || img.channels <= 0)
        fail(path, ": cannot write an empty image (", img.width, "x", img.height, "x", img.channels, ")");
    if (img.pixels.size() != img.pixelCount() * size_t(img.channels))
        fail(path, ": image has ", img.pixels.size(), " values, expected ", img.pixelCount() * size_t(img.channels));
}

/// Write the EXR file itself at `file` (a temporary); errors name `path`.
void writeEXRTo(const std::string& file, const std::string& path, const Image& img, const std::vector<std::string>& names,
                const ImageMetadata& meta) {
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
        Imf::OutputFile out(file.c_str(), header);
        out.setFrameBuffer(fb);
        out.writePixels(img.height);
    } catch (const std::exception& e) {
        fail(path, ": cannot write EXR: ", e.what());
    }
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

    writeFileAtomicallyWith(path, [&](const std::string& tmp) { writeEXRTo(tmp, path, img, names, meta); });
}

void writeLDR(const std::string& path, const Image& img) {
    checkWritable(path, img);
    std::string ext = std::filesystem::path(path).extension().string();
    for (char& ch : ext) ch = char(std::tolower(static_cast<unsigned char>(ch)));
    const bool noAlpha = ext == ".jpg" || ext == ".jpeg";  // JPEG has no alpha channel
    const int channels = std::min(img.channels, noAlpha ? 3 : 4);
    std::vector<unsigned char> bytes(img.pixelCount() * size_t(channels));
    for (size_t p = 0; p < img.pixelCount(); ++p)
        for (int c = 0; c < channels; ++c) {
            float v = img.pixels[p * size_t(img.channels) + size_t(c)];
            if (!(v > 0.0f)) v = 0.0f;  // also maps NaN to 0
            bytes[p * size_t(channels) + size_t(c)] = (unsigned char)std::lround(std::min(v, 1.0f) * 255.0f);
        }
    if (ext == ".png") {  // our own encoder: no OpenImageIO module to load (core/io/png_writer.h)
        const std::vector<uint8_t> png = encodePNG(img.width, img.height, channels, bytes.data());
        writeFileAtomically(path, std::string_view(reinterpret_cast<const char*>(png.data()), png.size()));
        return;
    }
    const OiioModule& oiio = oiioModule(path, "write this image");
    // The module picks the format from the real path's extension and writes the temp file.
    writeFileAtomicallyWith(path, [&](const std::string& tmp) {
        char err[1024] = "";
        if (!oiio.writeU8(path.c_str(), tmp.c_str(), img.width, img.height, channels, bytes.data(), err, sizeof(err)))
            fail(path, ": ", err);
    });
}

namespace {

/// An image may claim at most this many samples per byte of its file, plus kSmallImageSamples: a
/// header claiming more is refused before anything is allocated or decoded (found by fuzz_image: 134
/// bytes claiming > 1 GB; issue 38: a valid 97 KB DWAB EXR of 16384^2 pixels, 3 GiB as floats).
/// DEFLATE, the densest general coder of these formats, expands at most 1032:1 (RFC 1951: a
/// 258-byte match in 2 bits at best); OpenEXR's PIZ and DWA can go further only on images that are
/// (nearly) constant, which as textures or environment maps this large are better written small. The
/// allowance of 2^26 samples (256 MiB as floats) keeps such images up to 4096^2 RGBA readable.
constexpr uint64_t kSamplesPerFileByte = 2048;
constexpr uint64_t kSmallImageSamples = uint64_t(1) << 26;

/// The image's size from its header, checked against the pixel limit and the file's size. Returns
/// the number of samples.
uint64_t checkSizeLimits(const std::string& path, long long w, long long h, long long channels, uint64_t fileBytes) {
    if (w <= 0 || h <= 0 || channels <= 0) fail(path, ": unsupported image size ", w, "x", h, "x", channels);
    // Each factor first, so that the product cannot overflow.
    if (w > (long long)kMaxPixels || h > (long long)kMaxPixels || w * h > (long long)kMaxPixels)
        fail(path, ": image of ", w, "x", h, " pixels exceeds the limit of 2^28 pixels");
    if (channels > 1024) fail(path, ": absurd channel count ", channels);
    const uint64_t samples = uint64_t(w) * uint64_t(h) * uint64_t(channels);
    if (samples > kSamplesPerFileByte * fileBytes + kSmallImageSamples)
        fail(path, ": header claims ", w, "x", h, "x", channels, " samples (", formatBytes(samples * sizeof(float)),
             " as floats), more than a ", fileBytes, "-byte file can hold (at most ", kSamplesPerFileByte,
             " samples per byte beyond the first 2^26)");
    return samples;
}

/// checkSizeLimits, then the memory budget (charged) before the pixels are allocated.
void checkSize(const std::string& path, long long w, long long h, long long channels, uint64_t fileBytes) {
    const uint64_t samples = checkSizeLimits(path, w, h, channels, fileBytes);
    chargeMemory(samples * sizeof(float), strCat(path, ": image of ", w, "x", h, "x", channels, " floats"));
}

/// True if the file is an OpenEXR file without deep data: OpenEXR's test of the magic number
/// 20000630 and the version field (whose "non-image" bit marks deep parts; OpenEXR file layout,
/// openexr.com). Deep files are left to OpenImageIO, as before.
bool isFlatExr(const std::string& path) {
    bool tiled = false, deep = false;
    return Imf::isOpenExrFile(path.c_str(), tiled, deep) && !deep;
}

/// OpenImageIO's order of EXR channels (observed with iinfo on OpenImageIO 2.4, which reorders
/// OpenEXR's alphabetical channel list): by layer (the name up to its last '.'), then by the rank
/// of the suffix in a list of reserved names (case-insensitive; others after them), then by suffix.
/// Kept so that readImage returns EXR channels in the same order as before it used OpenEXR.
struct ExrChannelKey {
    std::string name, layer, suffix;
    int rank;
    explicit ExrChannelKey(const std::string& n) : name(n) {
        const size_t dot = n.find_last_of('.');
        layer = dot == std::string::npos ? std::string() : n.substr(0, dot + 1);
        suffix = dot == std::string::npos ? n : n.substr(dot + 1);
        static const char* const kReserved[] = {"R",  "Red", "G",  "Green", "B",  "Blue",  "Y",
                                                "real", "imag", "A", "Alpha", "AR", "RA", "AG",
                                                "GA", "AB",  "BA", "Z",     "Depth", "Zback"};
        rank = 1 << 20;
        for (int i = 0; i < int(std::size(kReserved)); ++i)
            if (::strcasecmp(suffix.c_str(), kReserved[i]) == 0) {
                rank = i;
                break;
            }
    }
    bool operator<(const ExrChannelKey& o) const {
        if (layer != o.layer) return layer < o.layer;
        if (rank != o.rank) return rank < o.rank;
        return suffix < o.suffix;
    }
};

/// Read an EXR file with OpenEXR: the first part's data window, every channel as float. Returns
/// false (nothing read) for what this path does not handle the same way as OpenImageIO: deep
/// data, subsampled channels and UINT channels (OpenImageIO normalises those); the caller then
/// reads the file through the module.
bool readExrDirect(const std::string& path, uint64_t fileBytes, Image& img) {
    try {
        Imf::InputFile file(path.c_str());
        const Imf::Header& header = file.header();
        if (header.hasType() && Imf::isDeepData(header.type())) return false;
        std::vector<ExrChannelKey> keys;
        for (auto it = header.channels().begin(); it != header.channels().end(); ++it) {
            const Imf::Channel& ch = it.channel();
            if (ch.type == Imf::UINT || ch.xSampling != 1 || ch.ySampling != 1) return false;
            keys.emplace_back(it.name());
        }
        const Imath::Box2i dw = header.dataWindow();
        const long long w = (long long)dw.max.x - dw.min.x + 1, h = (long long)dw.max.y - dw.min.y + 1;
        checkSize(path, w, h, (long long)keys.size(), fileBytes);
        std::sort(keys.begin(), keys.end());

        img = Image();
        img.width = int(w);
        img.height = int(h);
        img.channels = int(keys.size());
        img.channelNames.clear();
        for (const ExrChannelKey& k : keys) img.channelNames.push_back(k.name);
        img.pixels.assign(img.pixelCount() * size_t(img.channels), 0.0f);

        // OpenEXR addresses pixel (x, y) of the data window at base + x·xStride + y·yStride.
        Imf::FrameBuffer fb;
        const size_t xStride = sizeof(float) * size_t(img.channels);
        const size_t yStride = xStride * size_t(img.width);
        // Computed in unsigned integers: a data window far from the origin (a fuzzed header) puts this
        // pointer outside the buffer, which is undefined behaviour as pointer arithmetic; OpenEXR only
        // ever dereferences it inside the data window.
        const uintptr_t base = reinterpret_cast<uintptr_t>(img.pixels.data());
        char* origin = reinterpret_cast<char*>(base - uintptr_t(intptr_t(dw.min.x)) * xStride -
                                               uintptr_t(intptr_t(dw.min.y)) * yStride);
        for (int c = 0; c < img.channels; ++c)
            fb.insert(img.channelNames[size_t(c)],
                      Imf::Slice(Imf::FLOAT, origin + sizeof(float) * size_t(c), xStride, yStride));
        file.setFrameBuffer(fb);
        try {
            file.readPixels(dw.min.y, dw.max.y);
        } catch (const std::exception& e) {
            fail(path, ": cannot read pixels: ", e.what());
        }
        return true;
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        fail(path, ": cannot read image: ", e.what());
    }
}

/// Read any image through OpenImageIO (the module).
Image readThroughModule(const std::string& path, uint64_t fileBytes, ImageFileInfo* info) {
    checkPngChunkLengths(path);  // before libpng allocates what a chunk claims
    // Before OpenImageIO's WebP reader decodes (and allocates) the whole canvas inside open():
    // 4 channels of 8 bits, checked as floats like every other image (OpenImageIO converts them).
    if (const auto webp = webpCanvas(path)) checkSizeLimits(path, webp->width, webp->height, 4, fileBytes);
    const OiioModule& oiio = oiioModule(path, "read this image");
    char err[1024] = "";
    iris_oiio_info spec{};
    void* handle = oiio.open(path.c_str(), &spec, err, sizeof(err));
    if (!handle) fail(path, ": ", err);
    // Closes the handle on every exit, including the errors below.
    const std::unique_ptr<void, iris_oiio_close_fn> guard(handle, oiio.close);
    if (spec.depth > 1) fail(path, ": unsupported image size ", spec.width, "x", spec.height, "x", spec.channels);
    checkSize(path, spec.width, spec.height, spec.channels, fileBytes);

    Image img;
    img.width = spec.width;
    img.height = spec.height;
    img.channels = spec.channels;
    img.channelNames.clear();
    for (int c = 0; c < spec.channels; ++c) {
        const char* name = oiio.channelName(handle, c);
        img.channelNames.push_back(name && *name ? std::string(name) : strCat("C", c));
    }
    img.pixels.assign(img.pixelCount() * size_t(img.channels), 0.0f);
    if (!oiio.readFloat(handle, img.pixels.data(), err, sizeof(err))) fail(path, ": ", err);
    if (info) {
        info->integerFormat = spec.integer_format != 0;
        info->colorSpace = spec.color_space;
    }
    return img;
}

/// The checks every image read starts with, before OpenEXR or OpenImageIO sees the file: a regular
/// file (core/input_file.h; a device made OpenImageIO's format probe spin, issue 38) whose EXR
/// header sizes fit in it. Returns the file's size.
uint64_t checkImageFile(const std::string& path) {
    const uint64_t fileBytes = checkInputFile(path, "image");
    checkExrHeaderSizes(path, kMaxPixels);
    return fileBytes;
}

}  // namespace

Image readImage(const std::string& path, ImageFileInfo* info) {
    const uint64_t fileBytes = checkImageFile(path);
    if (isFlatExr(path)) {
        Image img;
        if (readExrDirect(path, fileBytes, img)) {
            if (info) *info = ImageFileInfo{};  // HALF/FLOAT: not an integer format
            return img;
        }
    }
    return readThroughModule(path, fileBytes, info);
}

Image readImageWithOpenImageIO(const std::string& path, ImageFileInfo* info) {
    return readThroughModule(path, checkImageFile(path), info);
}

ImageMetadata readEXRMetadata(const std::string& path) {
    checkImageFile(path);
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
