// Reading a glTF 2.0 file (.gltf with its buffers and images, or .glb) with tinygltf (Debian's
// libtinygltf-dev), and the checks every other glTF reader here relies on: the extensions the file
// requires or uses, and messages that name the file and the JSON path of the problem.
// All of the glTF importer's file reads go through readGltfBytes (one place: core/input_file's
// readInputFile, which refuses devices, FIFOs and directories and checks the memory budget).
#pragma once

#include <string>
#include <vector>

#include <tiny_gltf.h>

#include "core/error.h"

namespace iris::gltf {

struct Document {
    tinygltf::Model model;
    std::string path;  // the file as given, for messages
    std::string dir;   // the folder relative URIs resolve against
    std::vector<std::string> warnings;
};

/// "file: /json/path: message" as an iris::Error.
template <typename... Args>
[[noreturn]] void failAtPath(const Document& doc, const std::string& jsonPath, Args&&... args) {
    fail(doc.path, ": ", jsonPath, ": ", std::forward<Args>(args)...);
}

/// The extensions this importer implements (KHR_materials_*, KHR_lights_punctual,
/// KHR_texture_transform): docs/gltf.md.
const std::vector<std::string>& supportedExtensions();

/// Parse `path` (.glb by its magic number, else JSON). Throws iris::Error naming the file for a
/// parse error, a missing buffer or image, and for an extension in extensionsRequired that is not
/// supported; unsupported ones only in extensionsUsed are returned in Document::warnings.
Document readDocument(const std::string& path);

/// The same for a file's bytes held in memory: `name` is used in messages, relative URIs resolve
/// against `dir` (the fuzz target's entry point).
Document readDocumentFromBytes(const std::string& bytes, const std::string& name, const std::string& dir);

/// The bytes of a file a glTF refers to (or the glTF itself): core's readInputFile.
std::string readGltfBytes(const std::string& path);

}  // namespace iris::gltf
