// libFuzzer target: glTF 2.0 files (.gltf JSON or .glb, told apart by the magic number) through
// the whole importer (render/loader/gltf_*): tinygltf's parse, the extension checks, accessors,
// meshes, materials, images, nodes, cameras and lights. URIs resolve against a folder with no
// files, so external buffers and images fail as missing files.
#include "render/loader/gltf_loader.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string bytes(reinterpret_cast<const char*>(data), size);
    iris::GltfOptions options;
    options.width = 8;
    iris::fuzz::expectResultOrIrisError(
        [&] { iris::loadGltfSceneFromMemory(bytes, "fuzz.gltf", (iris::fuzz::scratchDir() / "no_files").string(), options); });
    return 0;
}
