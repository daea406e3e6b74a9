#include "render/loader/gltf_accessor.h"

#include <cstring>

#include "core/memory_budget.h"

namespace iris::gltf {

namespace {

/// A validated view of an accessor's bytes: element i starts at data + i·stride.
struct View {
    const unsigned char* data = nullptr;  // nullptr: no bufferView (all zeros, §5.1.1)
    size_t count = 0, stride = 0;
    int componentType = 0, components = 0;
    bool normalized = false;
};

size_t componentSize(int type) {
    switch (type) {
        case TINYGLTF_COMPONENT_TYPE_BYTE:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
        case TINYGLTF_COMPONENT_TYPE_SHORT:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
        default: return 0;
    }
}

const tinygltf::Accessor& accessorAt(const Document& doc, int index, const std::string& what) {
    if (index < 0 || size_t(index) >= doc.model.accessors.size())
        failAtPath(doc, what, "accessor ", index, " does not exist (the file has ", doc.model.accessors.size(), ")");
    return doc.model.accessors[size_t(index)];
}

View viewOf(const Document& doc, int index, const std::string& what) {
    const tinygltf::Accessor& a = accessorAt(doc, index, what);
    const std::string path = strCat("/accessors/", index);
    View v;
    v.componentType = a.componentType;
    v.components = componentCount(doc, index, what);
    v.normalized = a.normalized;
    v.count = a.count;
    const size_t csize = componentSize(a.componentType);
    if (csize == 0) failAtPath(doc, path + "/componentType", "unknown component type ", a.componentType);
    if (a.sparse.isSparse) failAtPath(doc, path + "/sparse", "sparse accessors are not supported");
    const size_t elem = csize * size_t(v.components);
    if (a.bufferView < 0) return v;
    if (size_t(a.bufferView) >= doc.model.bufferViews.size())
        failAtPath(doc, path + "/bufferView", "buffer view ", a.bufferView, " does not exist");
    const tinygltf::BufferView& bv = doc.model.bufferViews[size_t(a.bufferView)];
    const std::string bvPath = strCat("/bufferViews/", a.bufferView);
    if (bv.buffer < 0 || size_t(bv.buffer) >= doc.model.buffers.size()) failAtPath(doc, bvPath + "/buffer", "buffer ", bv.buffer, " does not exist");
    const size_t bufferSize = doc.model.buffers[size_t(bv.buffer)].data.size();
    if (bv.byteOffset > bufferSize || bv.byteLength > bufferSize - bv.byteOffset)
        failAtPath(doc, bvPath, "bytes ", bv.byteOffset, "..", bv.byteOffset + bv.byteLength, " lie beyond buffer ", bv.buffer, " (", bufferSize, " bytes)");
    v.stride = bv.byteStride ? bv.byteStride : elem;
    if (v.stride < elem) failAtPath(doc, bvPath + "/byteStride", "stride ", v.stride, " is smaller than the element (", elem, " bytes)");
    if (v.count > 0) {
        const size_t last = a.byteOffset + (v.count - 1) * v.stride;  // no overflow: count ≤ 2^32, stride ≤ 252
        if (a.byteOffset > bv.byteLength || last > bv.byteLength || elem > bv.byteLength - last)
            failAtPath(doc, path, "count ", v.count, " at offset ", a.byteOffset, " reaches beyond buffer view ", a.bufferView, " (", bv.byteLength, " bytes)");
    }
    v.data = doc.model.buffers[size_t(bv.buffer)].data.data() + bv.byteOffset + a.byteOffset;
    return v;
}

double component(const View& v, size_t i, int c) {
    if (!v.data) return 0.0;
    const unsigned char* p = v.data + i * v.stride + size_t(c) * componentSize(v.componentType);
    auto get = [p](auto t) {
        std::memcpy(&t, p, sizeof t);
        return t;
    };
    switch (v.componentType) {
        case TINYGLTF_COMPONENT_TYPE_BYTE: { const double x = get(int8_t()); return v.normalized ? std::max(x / 127.0, -1.0) : x; }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: { const double x = get(uint8_t()); return v.normalized ? x / 255.0 : x; }
        case TINYGLTF_COMPONENT_TYPE_SHORT: { const double x = get(int16_t()); return v.normalized ? std::max(x / 32767.0, -1.0) : x; }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: { const double x = get(uint16_t()); return v.normalized ? x / 65535.0 : x; }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return get(uint32_t());
        default: return get(float());
    }
}

}  // namespace

int componentCount(const Document& doc, int index, const std::string& what) {
    const int n = tinygltf::GetNumComponentsInType(uint32_t(accessorAt(doc, index, what).type));
    if (n <= 0) failAtPath(doc, strCat("/accessors/", index, "/type"), "unknown accessor type");
    return n;
}

std::vector<float> readFloats(const Document& doc, int index, int components, const std::string& what) {
    const View v = viewOf(doc, index, what);
    if (v.components != components)
        failAtPath(doc, what, "accessor ", index, " has ", v.components, " components per element, expected ", components);
    if (!v.data && v.count > (size_t(1) << 26)) failAtPath(doc, strCat("/accessors/", index), "count ", v.count, " without data is too large");
    chargeMemory(uint64_t(v.count) * uint64_t(components) * sizeof(float), strCat(doc.path, ": accessor ", index));
    std::vector<float> out(v.count * size_t(components));
    for (size_t i = 0; i < v.count; ++i)
        for (int c = 0; c < components; ++c) out[i * size_t(components) + size_t(c)] = float(component(v, i, c));
    return out;
}

std::vector<uint32_t> readIndices(const Document& doc, int index, uint32_t limit, const std::string& what) {
    const View v = viewOf(doc, index, what);
    const std::string path = strCat("/accessors/", index);
    if (v.components != 1) failAtPath(doc, path, "indices must be SCALAR");
    if (v.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && v.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        v.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
        failAtPath(doc, path + "/componentType", "indices must be unsigned integers");
    if (!v.data) failAtPath(doc, path, "indices need a buffer view");
    chargeMemory(uint64_t(v.count) * sizeof(uint32_t), strCat(doc.path, ": accessor ", index));
    std::vector<uint32_t> out(v.count);
    for (size_t i = 0; i < v.count; ++i) {
        const double x = component(v, i, 0);
        if (!(x < double(limit))) failAtPath(doc, strCat(path, "[", i, "]"), "index ", x, " is out of range (", limit, " vertices) in ", what);
        out[i] = uint32_t(x);
    }
    return out;
}

}  // namespace iris::gltf
