// A check of PNG chunk lengths before OpenImageIO (libpng) reads a PNG: every chunk's declared
// length must fit in the file. libpng allocates a chunk's declared length before reading it, so
// a 104-byte file claiming a 1.7 GB chunk allocated 1.7 GB (found by fuzz_image). Layout (PNG
// specification, ISO/IEC 15948 §5.3): an 8-byte signature, then chunks "uint32 length (big
// endian), 4-byte type, data, uint32 CRC", the last one IEND.
#pragma once

#include <string>

namespace iris {

/// Throws iris::Error "path: corrupt PNG: chunk 'TYPE' claims N bytes, M are left" if a chunk
/// claims more bytes than the file has left. Files without the PNG signature pass.
void checkPngChunkLengths(const std::string& path);

}  // namespace iris
