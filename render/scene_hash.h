// A short identifier of what a scene file renders: FNV-1a (64 bit) over the bytes of the scene file
// and its -D overrides. Shards of one split render must agree on it (docs/cluster.md); files the
// scene includes or reads (meshes, textures) are not hashed.
#pragma once

#include <map>
#include <string>

namespace iris {

/// 16 hex digits. Throws iris::Error naming the file if it cannot be read.
std::string sceneHash(const std::string& scenePath, const std::map<std::string, std::string>& defines);

}  // namespace iris
