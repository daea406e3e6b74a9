#include "core/io/whole_file.h"

#include <fstream>

#include "core/error.h"
#include "core/memory_budget.h"

namespace iris {

std::string readWholeFile(const std::string& path, const std::string& kind) {
    std::ifstream in(path, std::ios::binary | std::ios::ate);
    if (!in) fail(path, ": cannot open ", kind);
    const std::streamoff size = in.tellg();
    if (size < 0) fail(path, ": cannot tell the size of the ", kind);
    checkMemory(uint64_t(size), strCat(path, ": reading the ", kind));  // freed once parsed
    std::string data(size_t(size), '\0');
    in.seekg(0);
    in.read(data.data(), size);
    if (in.gcount() != size) fail(path, ": read error (", in.gcount(), " of ", size, " bytes)");
    return data;
}

}  // namespace iris
