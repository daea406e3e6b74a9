// Float images and their files: OpenEXR output (with string metadata), 8-bit LDR output and reading
// of anything OpenImageIO understands. EXR goes through OpenEXR, PNG output through iris's own
// encoder (core/io/png_writer.h); JPEG output and other formats go through the OpenImageIO
// module, loaded on first use (core/io/oiio_loader.h). Library headers stay in image.cpp.
#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace iris {

/// A float image with C channels per pixel, row-major, top row first.
struct Image {
    int width = 0, height = 0, channels = 3;
    std::vector<float> pixels;
    std::vector<std::string> channelNames;  // e.g. {"R","G","B"}; optional extra AOV-like channels allowed

    Image() = default;
    /// A zero-filled image; channel names default to R,G,B(,A) / Y / C0.. by channel count.
    Image(int w, int h, int c = 3);

    size_t index(int x, int y, int c) const { return (size_t(y) * size_t(width) + size_t(x)) * size_t(channels) + size_t(c); }
    float& at(int x, int y, int c) { return pixels[index(x, y, c)]; }
    float at(int x, int y, int c) const { return pixels[index(x, y, c)]; }
    size_t pixelCount() const { return size_t(width) * size_t(height); }
    /// Channel index of `name`, or -1.
    int channelIndex(const std::string& name) const;
};

/// Default channel names for a channel count: 1 → Y, 3 → R,G,B, 4 → R,G,B,A, else C0, C1, ...
std::vector<std::string> defaultChannelNames(int channels);

/// String metadata recorded in the EXR header (key → value).
using ImageMetadata = std::vector<std::pair<std::string, std::string>>;

/// Value of `key` in `meta`, or `def` when absent.
std::string metadataValue(const ImageMetadata& meta, const std::string& key, const std::string& def = {});

/// Write an OpenEXR file with OpenEXR (FLOAT channels, ZIP compression) and the metadata as string
/// attributes, atomically (core/io/atomic_file.h). Throws iris::Error naming the file.
void writeEXR(const std::string& path, const Image& img, const ImageMetadata& meta = {});

/// Write an 8-bit LDR image (PNG/JPEG by extension; PNG with core/io/png_writer.h, anything else
/// through the OpenImageIO module); input values
/// are display code values in [0,1] (clamped, rounded); atomic as above. Throws iris::Error naming
/// the file, also when the module cannot be loaded.
void writeLDR(const std::string& path, const Image& img);

/// What a reader learned about the stored pixel format (for sRGB decoding of textures).
struct ImageFileInfo {
    bool integerFormat = false;  // stored as 8- or 16-bit unsigned integers
    std::string colorSpace;      // OpenImageIO's "oiio:ColorSpace" attribute ("" if none / EXR)
};

/// Read any image OpenImageIO reads (EXR, HDR, PNG, ...) as linear float as stored (no colour conversion);
/// throws iris::Error "path: <reason>" for missing/unreadable/corrupt/truncated files, absurd sizes (refuse > 2^28 pixels).
/// Files with the OpenEXR magic number are read with OpenEXR (first part, data window, channels in
/// OpenImageIO's order: by layer, then R, G, B, A, ..., then the rest); other files, and the
/// EXR variants OpenImageIO converts differently (deep, subsampled, UINT channels), go through the
/// OpenImageIO module. `info`, if given, receives the stored pixel format.
Image readImage(const std::string& path, ImageFileInfo* info = nullptr);

/// The general path of readImage for every file, EXR included: always through the OpenImageIO
/// module (tests compare the OpenEXR path against it).
Image readImageWithOpenImageIO(const std::string& path, ImageFileInfo* info = nullptr);

/// Read the string attributes of an EXR header (in header order, which OpenEXR sorts by name).
ImageMetadata readEXRMetadata(const std::string& path);

}  // namespace iris
