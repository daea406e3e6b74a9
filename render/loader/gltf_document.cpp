#include "render/loader/gltf_document.h"

#include <algorithm>
#include <filesystem>

#include "core/input_file.h"

namespace iris::gltf {

namespace {

/// A URI that is no file name at all (too long, say) is a missing file, not an exception: the
/// error_code overload never throws.
bool fileExists(const std::string& path, void*) {
    std::error_code ec;
    return std::filesystem::is_regular_file(path, ec);
}

std::string expandPath(const std::string& path, void*) { return path; }

bool readFileCallback(std::vector<unsigned char>* out, std::string* err, const std::string& path, void*) {
    try {
        const std::string bytes = readGltfBytes(path);
        out->assign(bytes.begin(), bytes.end());
        return true;
    } catch (const Error& e) {
        if (err) *err += std::string(e.what()) + "\n";
        return false;
    }
}

bool refuseWrite(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
    if (err) *err += "writing files is not allowed while importing\n";
    return false;
}

/// Images are kept encoded (as_is): render/loader/gltf_images decodes them with core's readers.
bool keepEncoded(tinygltf::Image* image, int, std::string*, std::string*, int, int, const unsigned char* bytes, int size, void*) {
    if (size < 0) return false;
    image->image.assign(bytes, bytes + size);
    image->as_is = true;
    return true;
}

/// tinygltf's messages, one line each, without empty lines.
std::string tidy(const std::string& text) {
    std::string out;
    size_t start = 0;
    while (start < text.size()) {
        size_t end = text.find('\n', start);
        if (end == std::string::npos) end = text.size();
        const std::string line = text.substr(start, end - start);
        if (!line.empty()) out += (out.empty() ? "" : "; ") + line;
        start = end + 1;
    }
    return out;
}

bool isGlb(const std::string& bytes) { return bytes.size() >= 4 && bytes.compare(0, 4, "glTF") == 0; }

void checkExtensions(Document& doc) {
    const std::vector<std::string>& ok = supportedExtensions();
    auto supported = [&](const std::string& e) { return std::find(ok.begin(), ok.end(), e) != ok.end(); };
    for (size_t i = 0; i < doc.model.extensionsRequired.size(); ++i)
        if (!supported(doc.model.extensionsRequired[i]))
            failAtPath(doc, strCat("/extensionsRequired/", i), "extension '", doc.model.extensionsRequired[i],
                       "' is required by the file and not supported (docs/gltf.md lists the supported ones)");
    std::string unsupported;
    for (const std::string& e : doc.model.extensionsUsed)
        if (!supported(e)) unsupported += (unsupported.empty() ? "" : ", ") + e;
    if (!unsupported.empty())
        doc.warnings.push_back(strCat(doc.path, ": /extensionsUsed: ignoring unsupported extensions: ", unsupported));
}

}  // namespace

const std::vector<std::string>& supportedExtensions() {
    static const std::vector<std::string> names = {
        "KHR_materials_ior",        "KHR_materials_specular", "KHR_materials_transmission", "KHR_materials_clearcoat",
        "KHR_materials_sheen",      "KHR_materials_iridescence", "KHR_materials_emissive_strength", "KHR_materials_volume",
        "KHR_lights_punctual",      "KHR_texture_transform"};
    return names;
}

std::string readGltfBytes(const std::string& path) { return readInputFile(path, "glTF file"); }

Document readDocument(const std::string& path) {
    return readDocumentFromBytes(readGltfBytes(path), path, std::filesystem::path(path).parent_path().string());
}

Document readDocumentFromBytes(const std::string& bytes, const std::string& path, const std::string& dir) {
    Document doc;
    doc.path = path;
    doc.dir = dir;
    tinygltf::TinyGLTF reader;
    reader.SetFsCallbacks({&fileExists, &expandPath, &readFileCallback, &refuseWrite, nullptr});
    reader.SetImageLoader(&keepEncoded, nullptr);
    std::string err, warn;
    const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
    const bool ok = isGlb(bytes)
                        ? reader.LoadBinaryFromMemory(&doc.model, &err, &warn, data, unsigned(bytes.size()), doc.dir)
                        : reader.LoadASCIIFromString(&doc.model, &err, &warn, bytes.data(), unsigned(bytes.size()), doc.dir);
    if (!ok || !err.empty()) fail(path, ": cannot read glTF: ", tidy(err.empty() ? "unknown error" : err));
    if (!warn.empty()) doc.warnings.push_back(strCat(path, ": ", tidy(warn)));
    checkExtensions(doc);
    return doc;
}

}  // namespace iris::gltf
