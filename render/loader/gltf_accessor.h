// glTF accessors (glTF 2.0 §3.6 "Binary Data Storage", §5.1 accessor) read as floats or indices
// after checking that every byte they address lies inside their buffer view and buffer, so a
// hostile count or offset is an error naming the file and JSON path, never a read out of bounds
// or an allocation the data does not back.
#pragma once

#include <cstdint>
#include <vector>

#include "render/loader/gltf_document.h"

namespace iris::gltf {

/// The elements of accessor `index` as floats, `components` per element (the accessor's type
/// must have that many: VEC3 for 3, ...). Normalized integer types map to [0, 1] / [−1, 1]
/// (§3.11 "Animations"/§5.1.1 accessor.normalized). `what` names the use in messages
/// ("/meshes/0/primitives/1/attributes/POSITION").
std::vector<float> readFloats(const Document& doc, int index, int components, const std::string& what);

/// The elements of a SCALAR accessor of unsigned integers (indices, §3.7.2.1), each checked < limit.
std::vector<uint32_t> readIndices(const Document& doc, int index, uint32_t limit, const std::string& what);

/// The number of components of accessor `index` (1 for SCALAR ... 16 for MAT4).
int componentCount(const Document& doc, int index, const std::string& what);

}  // namespace iris::gltf
