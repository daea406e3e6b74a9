#include "render/loader/gltf_mesh.h"

#include "materials/gltf_texture.h"
#include "render/loader/gltf_accessor.h"

namespace iris::gltf {

namespace {

/// Triangle indices from the primitive's index list (or 0..n−1) by its mode (§3.7.2.1: strips
/// alternate their winding, fans share the first vertex).
std::vector<uint32_t> triangulate(const std::vector<uint32_t>& idx, int mode) {
    std::vector<uint32_t> out;
    if (mode == TINYGLTF_MODE_TRIANGLES) {
        out.assign(idx.begin(), idx.begin() + ptrdiff_t(idx.size() / 3 * 3));
    } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
        for (size_t i = 2; i < idx.size(); ++i) {
            const bool even = (i % 2) == 0;
            out.insert(out.end(), {idx[i - 2], even ? idx[i - 1] : idx[i], even ? idx[i] : idx[i - 1]});
        }
    } else {  // TRIANGLE_FAN
        for (size_t i = 2; i < idx.size(); ++i) out.insert(out.end(), {idx[0], idx[i - 1], idx[i]});
    }
    return out;
}

int attribute(const tinygltf::Primitive& prim, const char* name) {
    const auto it = prim.attributes.find(name);
    return it == prim.attributes.end() ? -1 : it->second;
}

void addAttribute(Document& doc, TriangleMesh& mesh, int accessor, const char* name, int components, const std::string& path) {
    MeshAttribute a;
    a.name = name;
    a.channels = components;
    a.values = readFloats(doc, accessor, components, path);
    if (a.values.size() != mesh.positions.size() * size_t(components))
        failAtPath(doc, path, "has ", a.values.size() / size_t(components), " elements, POSITION has ", mesh.positions.size());
    mesh.attributes.push_back(std::move(a));
}

}  // namespace

std::optional<TriangleMesh> readPrimitive(Document& doc, int m, int p) {
    const tinygltf::Primitive& prim = doc.model.meshes[size_t(m)].primitives[size_t(p)];
    const std::string path = strCat("/meshes/", m, "/primitives/", p);
    if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != TINYGLTF_MODE_TRIANGLE_STRIP && prim.mode != TINYGLTF_MODE_TRIANGLE_FAN) {
        doc.warnings.push_back(strCat(doc.path, ": ", path, "/mode: points and lines are not rendered (mode ", prim.mode, ")"));
        return std::nullopt;
    }
    const int pos = attribute(prim, "POSITION");
    if (pos < 0) failAtPath(doc, path + "/attributes", "POSITION is missing");
    TriangleMesh mesh;
    mesh.name = strCat(doc.path, ":", path);
    const std::vector<float> xyz = readFloats(doc, pos, 3, path + "/attributes/POSITION");
    for (size_t i = 0; i + 2 < xyz.size(); i += 3) mesh.positions.emplace_back(xyz[i], xyz[i + 1], xyz[i + 2]);
    const size_t n = mesh.positions.size();
    if (const int a = attribute(prim, "NORMAL"); a >= 0) {
        const std::vector<float> v = readFloats(doc, a, 3, path + "/attributes/NORMAL");
        if (v.size() != 3 * n) failAtPath(doc, path + "/attributes/NORMAL", "count differs from POSITION's");
        for (size_t i = 0; i < n; ++i) mesh.normals.emplace_back(v[3 * i], v[3 * i + 1], v[3 * i + 2]);
    }
    if (const int a = attribute(prim, "TEXCOORD_0"); a >= 0) {
        const std::vector<float> v = readFloats(doc, a, 2, path + "/attributes/TEXCOORD_0");
        if (v.size() != 2 * n) failAtPath(doc, path + "/attributes/TEXCOORD_0", "count differs from POSITION's");
        for (size_t i = 0; i < n; ++i) mesh.uvs.emplace_back(v[2 * i], v[2 * i + 1]);
    }
    if (const int a = attribute(prim, "TEXCOORD_1"); a >= 0) addAttribute(doc, mesh, a, kTexCoord1Attribute, 2, path + "/attributes/TEXCOORD_1");
    if (const int a = attribute(prim, "TANGENT"); a >= 0) addAttribute(doc, mesh, a, kTangentAttribute, 4, path + "/attributes/TANGENT");
    if (const int a = attribute(prim, "COLOR_0"); a >= 0) {
        const int channels = componentCount(doc, a, path + "/attributes/COLOR_0");
        if (channels != 3 && channels != 4) failAtPath(doc, path + "/attributes/COLOR_0", "must be VEC3 or VEC4");
        addAttribute(doc, mesh, a, kColorAttribute, channels, path + "/attributes/COLOR_0");
    }
    std::vector<uint32_t> idx;
    if (prim.indices >= 0) {
        idx = readIndices(doc, prim.indices, uint32_t(n), path + "/indices");
    } else {
        idx.resize(n);
        for (size_t i = 0; i < n; ++i) idx[i] = uint32_t(i);
    }
    mesh.indices = triangulate(idx, prim.mode);
    mesh.validate();
    return mesh;
}

void transformTangents(TriangleMesh& mesh, const mat4& m) {
    const mat3 linear(m);
    const float handedness = glm::determinant(linear) < 0 ? -1.0f : 1.0f;
    for (MeshAttribute& a : mesh.attributes) {
        if (a.name != kTangentAttribute || a.channels != 4) continue;
        for (size_t i = 0; i + 3 < a.values.size(); i += 4) {
            vec3 t = linear * vec3(a.values[i], a.values[i + 1], a.values[i + 2]);
            const float len = glm::length(t);
            if (len > 0 && std::isfinite(len)) t /= len;
            a.values[i] = t.x, a.values[i + 1] = t.y, a.values[i + 2] = t.z;
            a.values[i + 3] *= handedness;
        }
    }
}

}  // namespace iris::gltf
