// The OpenImageIO module (libiris_oiio.so): the only code linked to OpenImageIO. Built as a CMake
// MODULE (not part of the `iris` library) and loaded on demand by core/io/oiio_loader.cpp; the
// interface is the C ABI in core/io/oiio_module.h. No exception leaves these functions.
#include "core/io/oiio_module.h"

#include <cstdio>
#include <cstring>
#include <exception>
#include <memory>
#include <string>

#include <OpenImageIO/imageio.h>

#define IRIS_OIIO_EXPORT extern "C" __attribute__((visibility("default")))

namespace {

void setError(char* err, size_t errlen, const std::string& msg) {
    if (!err || errlen == 0) return;
    std::snprintf(err, errlen, "%s", msg.c_str());
}

struct OpenImage {
    std::unique_ptr<OIIO::ImageInput> in;
};

/// fn() across the C boundary: an exception becomes "<what>: <message>" in err and `failed` is
/// returned.
template <typename R, typename Fn>
R guarded(char* err, size_t errlen, const char* what, R failed, Fn&& fn) {
    try {
        return fn();
    } catch (const std::exception& e) {
        setError(err, errlen, std::string(what) + ": " + e.what());
    } catch (...) {
        setError(err, errlen, std::string(what) + ": unknown error");
    }
    return failed;
}

}  // namespace

IRIS_OIIO_EXPORT int iris_oiio_abi_version(void) { return IRIS_OIIO_ABI_VERSION; }

IRIS_OIIO_EXPORT int iris_oiio_write_u8(const char* format_path, const char* out_path, int width, int height,
                                        int channels, const unsigned char* pixels, char* err, size_t errlen) {
    return guarded(err, errlen, "cannot write image", 0, [&] {
        // The plug-in is chosen from the real path's extension; the data then goes to out_path.
        auto out = OIIO::ImageOutput::create(format_path);
        if (!out) {
            setError(err, errlen, "cannot write this image format: " + OIIO::geterror());
            return 0;
        }
        const OIIO::ImageSpec spec(width, height, channels, OIIO::TypeDesc::UINT8);
        if (!out->open(out_path, spec)) {
            setError(err, errlen, "cannot open for writing: " + out->geterror());
            return 0;
        }
        const bool ok = out->write_image(OIIO::TypeDesc::UINT8, pixels);
        const std::string writeErr = ok ? std::string() : out->geterror();
        const bool closed = out->close();
        if (!ok || !closed) {
            setError(err, errlen, "cannot write image: " + (ok ? out->geterror() : writeErr));
            return 0;
        }
        return 1;
    });
}

IRIS_OIIO_EXPORT void* iris_oiio_open(const char* path, iris_oiio_info* info, char* err, size_t errlen) {
    return guarded(err, errlen, "cannot read image", static_cast<void*>(nullptr), [&]() -> void* {
        auto image = std::make_unique<OpenImage>();
        // Colour as stored, not multiplied by alpha (OpenImageIO associates alpha by default):
        // Mitsuba reads PNG/TIFF colour unassociated and ignores alpha in textures (Mitsuba 3
        // textures/bitmap.cpp converts with AlphaTransform::Empty), e.g. a grey + alpha opacity mask.
        OIIO::ImageSpec config;
        config.attribute("oiio:UnassociatedAlpha", 1);
        image->in = OIIO::ImageInput::open(path, &config);
        // Discard any error state the new reader starts with, so that has_error() after the reads
        // below describes those reads only: OpenImageIO keeps unretrieved errors per thread outside
        // the reader, and a new reader could inherit a destroyed one's (OpenImageIO pull request
        // 4239, 2024, "Error retrieval safeguards for recycled objects", fixed one such case).
        if (image->in) (void)image->in->geterror();
        if (!image->in) {
            std::string e = OIIO::geterror();
            if (e.empty()) e = "not a readable image";
            setError(err, errlen, "cannot read image: " + e);
            return nullptr;
        }
        const OIIO::ImageSpec& spec = image->in->spec();
        *info = iris_oiio_info{};
        info->width = spec.width;
        info->height = spec.height;
        info->depth = spec.depth;
        info->channels = spec.nchannels;
        info->integer_format =
            spec.format.basetype == OIIO::TypeDesc::UINT8 || spec.format.basetype == OIIO::TypeDesc::UINT16;
        const std::string cs = spec.get_string_attribute("oiio:ColorSpace");
        std::snprintf(info->color_space, sizeof(info->color_space), "%s", cs.c_str());
        return image.release();
    });
}

IRIS_OIIO_EXPORT const char* iris_oiio_channel_name(void* handle, int c) {
    const OIIO::ImageSpec& spec = static_cast<OpenImage*>(handle)->in->spec();
    return c >= 0 && c < int(spec.channelnames.size()) ? spec.channelnames[size_t(c)].c_str() : "";
}

IRIS_OIIO_EXPORT int iris_oiio_read_float(void* handle, float* out, char* err, size_t errlen) {
    return guarded(err, errlen, "cannot read pixels", 0, [&] {
        OIIO::ImageInput& in = *static_cast<OpenImage*>(handle)->in;
        const OIIO::ImageSpec& spec = in.spec();
        // Scanline files one scanline at a time: read_image converts them through a buffer of a
        // whole strip (64 rows or more) of the widest scanline, so a 2-row EXR 4194306 pixels wide
        // allocated 12.9 GB (found by fuzz_image). Tiled files tile by tile, as read_image does.
        bool ok = true;
        if (spec.tile_width > 0) {
            ok = in.read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, out);
        } else {
            const size_t row = size_t(spec.width) * size_t(spec.nchannels);
            for (int y = 0; ok && y < spec.height; ++y)
                ok = in.read_scanline(spec.y + y, spec.z, OIIO::TypeDesc::FLOAT, out + size_t(y) * row);
        }
        if (!ok || in.has_error()) {
            std::string e = in.geterror();
            if (e.empty()) e = "corrupt or truncated pixel data (the reader failed without a message)";
            setError(err, errlen, "cannot read pixels: " + e);
            return 0;
        }
        return 1;
    });
}

IRIS_OIIO_EXPORT void iris_oiio_close(void* handle) {
    if (!handle) return;
    auto* image = static_cast<OpenImage*>(handle);
    try {
        image->in->close();
    } catch (...) {
    }
    delete image;
}
