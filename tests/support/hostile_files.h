// Hostile files made by the tests of issue 38 (tests/core/test_input_file.cpp,
// tests/apps/test_hostile_files.cpp): a FIFO, and a valid OpenEXR image that is small on disk and
// huge in memory.
#pragma once

#include <sys/stat.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>

namespace iris::testing {

/// A FIFO (named pipe) at `path`, replacing any file there; no process writes to it, so an open
/// for reading without O_NONBLOCK would wait for ever.
inline std::string makeFifo(const std::string& path) {
    std::remove(path.c_str());
    ::mkfifo(path.c_str(), 0644);
    return path;
}

/// A valid DWAB-compressed OpenEXR image of size×size constant RGB float pixels (size a multiple of
/// 256), the file of issue 38: at 16384 it is 97529 bytes on disk and 3 GiB as floats. OpenEXR takes
/// seconds to compress 2^28 pixels, so only the first chunk (DWAB's 256 scan lines) is compressed:
/// OpenEXR writes the header, the line offset table and that chunk, and the other chunks, identical
/// but for their first scan line, are appended here with their offsets filled in (OpenEXR file
/// layout: a table of 64-bit chunk offsets after the header; a chunk is an int32 y, an int32 size
/// and the data). Reading it back with OpenEXR gives every pixel 0.5.
inline void writeConstantDwabExr(const std::string& path, int size) {
    const int linesPerChunk = 256, chunks = size / linesPerChunk;
    std::vector<float> row(size_t(size), 0.5f);
    {
        Imf::Header header(size, size);
        header.compression() = Imf::DWAB_COMPRESSION;
        Imf::FrameBuffer fb;
        for (const char* c : {"R", "G", "B"}) {
            header.channels().insert(c, Imf::Channel(Imf::FLOAT));
            fb.insert(c, Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(row.data()), sizeof(float), 0));  // every line the same
        }
        Imf::OutputFile out(path.c_str(), header);
        out.setFrameBuffer(fb);
        out.writePixels(linesPerChunk);
    }  // closing writes the offset table: the first entry set, the others 0
    std::ifstream in(path, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    const std::string partial = ss.str();
    // The table is where a 64-bit value equals its own position plus the table's length: the first
    // entry, the offset of the first chunk, which follows the table.
    size_t table = 0;
    uint64_t first = 0;
    for (; table + 8 <= partial.size(); ++table) {
        std::memcpy(&first, partial.data() + table, 8);
        if (first == table + 8 * uint64_t(chunks)) break;
    }
    const std::string chunk = partial.substr(first);
    std::string file = partial.substr(0, first);
    for (int k = 0; k < chunks; ++k) {
        const uint64_t offset = file.size();
        std::memcpy(&file[table + 8 * size_t(k)], &offset, 8);
        std::string c = chunk;
        const int32_t y = k * linesPerChunk;
        std::memcpy(&c[0], &y, 4);
        file += c;
    }
    std::ofstream(path, std::ios::binary | std::ios::trunc) << file;
}

}  // namespace iris::testing
