// A check of OpenEXR headers before OpenEXR (or OpenImageIO) reads them: every attribute's
// declared size must fit in the file. OpenEXR 3.1 allocates an attribute's declared size before
// reading it, so a 100-byte file claiming a 1.6 GB attribute allocated 1.6 GB (found by
// fuzz_image). Layout (OpenEXR file layout document, "Header"): magic 76 2f 31 01, a 4-byte
// version/flags field, then per part a list of attributes "name\0 type\0 int32 size, value",
// closed by an empty name; multi-part files (flag 0x1000) end the list of headers with one more
// empty name.
#pragma once

#include <cstdint>
#include <string>

namespace iris {

/// True if the file starts with the OpenEXR magic number.
bool hasExrMagic(const std::string& path);

/// Throws iris::Error "path: corrupt EXR header: ..." if an attribute name is unterminated or an
/// attribute claims more bytes than the file has left, "path: image of ... exceeds the limit" if a
/// data window exceeds `maxPixels` (a power of two), and "path: EXR data window ..." / "path: EXR
/// tiles ..." if a buffer OpenEXR allocates on opening (one block of scan lines of the compression,
/// or one tile) would exceed 1 GB. Files without the EXR magic pass.
void checkExrHeaderSizes(const std::string& path, uint64_t maxPixels);

}  // namespace iris
