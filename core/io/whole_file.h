// Reading a whole input file into memory, its size checked against the memory budget first
// (core/memory_budget.h; checked, not held: the bytes are freed once parsed): the mesh readers parse from the bytes in memory.
#pragma once

#include <string>

namespace iris {

/// The bytes of `path`. `kind` names the format in messages ("PLY file"): "path: cannot open PLY
/// file", "path: read error". Throws iris::Error, also when the file does not fit the budget.
std::string readWholeFile(const std::string& path, const std::string& kind);

}  // namespace iris
