// The canvas size a WebP file claims, read before OpenImageIO opens it: OpenImageIO's WebP reader
// (2.4) decodes the whole image inside open(), allocating width·height·4 bytes from the header
// first, and libwebp accepts a bare VP8/VP8L bitstream without its RIFF container, so a 12-byte
// header claiming 12761x12401 pixels allocated 633 MB (found by fuzz_image). OpenImageIO also
// probes every reader on a file whose extension it does not know, so any file may reach it.
#pragma once

#include <optional>
#include <string>

namespace iris {

struct WebpCanvas {
    long long width = 0, height = 0;
};

/// The canvas width and height of a WebP file in either form libwebp decodes (WebP container
/// specification, RFC 9649 §2.5–2.7; VP8L bitstream RFC 9649 §3.2.1 "image width/height - 1" in
/// 14 bits each after the 0x2f signature; VP8 frame header RFC 6386 §9.1: 14-bit sizes after the
/// start code 9d 01 2a): "RIFF....WEBP" with a first chunk VP8X (24-bit canvas size − 1), "VP8 "
/// or "VP8L", or a bare VP8L or VP8 bitstream. Nothing for any other file.
std::optional<WebpCanvas> webpCanvas(const std::string& path);

}  // namespace iris
