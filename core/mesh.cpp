#include "core/mesh.h"

#include <array>
#include <bit>
#include <map>

#include "core/error.h"

namespace iris {

int MeshAttribute::elements(const TriangleMesh& mesh, size_t tri, vec2 b, size_t element[3], float weight[3]) const {
    if (perFace()) {
        element[0] = tri;
        weight[0] = 1.0f;
        return 1;
    }
    // Mitsuba 3 Mesh::interpolate_attribute: v0 b0 + v1 b1 + v2 b2 with b0 = 1 − b1 − b2.
    for (int k = 0; k < 3; ++k) element[k] = mesh.indices[3 * tri + size_t(k)];
    weight[0] = 1.0f - b.x - b.y, weight[1] = b.x, weight[2] = b.y;
    return 3;
}

float MeshAttribute::at(const TriangleMesh& mesh, size_t tri, vec2 b, int c) const {
    size_t element[3];
    float weight[3];
    const int n = elements(mesh, tri, b, element, weight);
    float v = 0.0f;
    for (int k = 0; k < n; ++k) v += weight[k] * value(element[k], c);
    return v;
}

void TriangleMesh::transform(const mat4& m) {
    for (vec3& p : positions) p = transformPoint(m, p);
    const mat3 nm = normalMatrix(m);
    for (vec3& n : normals) {
        n = nm * n;
        const float len = glm::length(n);
        if (len > 0) n /= len;
    }
    // A mirroring transform flips the winding; keep geometric normals consistent with normals.
    if (glm::determinant(mat3(m)) < 0)
        for (size_t i = 0; i + 2 < indices.size(); i += 3) std::swap(indices[i + 1], indices[i + 2]);
}

void TriangleMesh::flipNormals() {
    for (size_t i = 0; i + 2 < indices.size(); i += 3) std::swap(indices[i + 1], indices[i + 2]);
    for (vec3& n : normals) n = -n;
}

void TriangleMesh::validate() const {
    if (indices.size() % 3 != 0) fail(name, ": index count is not a multiple of 3");
    const size_t nv = positions.size();
    for (uint32_t i : indices)
        if (i >= nv) fail(name, ": vertex index ", i, " out of range (", nv, " vertices)");
    if (!normals.empty() && normals.size() != nv) fail(name, ": normal count differs from vertex count");
    if (!uvs.empty() && uvs.size() != nv) fail(name, ": uv count differs from vertex count");
    for (const vec3& p : positions)
        if (!isFinite(p)) fail(name, ": non-finite vertex position");
    for (const MeshAttribute& a : attributes) {
        const size_t count = a.perFace() ? triangleCount() : nv;
        if (a.channels < 1 || a.values.size() != count * size_t(a.channels))
            fail(name, ": attribute '", a.name, "' has ", a.values.size(), " values for ", count, " elements");
    }
}

TriangleMesh makeRectangle() {
    TriangleMesh m;
    m.name = "rectangle";
    m.positions = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
    m.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
    m.uvs = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    m.indices = {0, 1, 2, 0, 2, 3};
    return m;
}

TriangleMesh makeCube() {
    TriangleMesh m;
    m.name = "cube";
    // Six faces, four vertices each, so that face normals are exact.
    const vec3 normals[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    for (const vec3& n : normals) {
        const vec3 a = std::abs(n.x) > 0.5f ? vec3(0, 1, 0) : vec3(1, 0, 0);
        const vec3 u = glm::cross(a, n), v = glm::cross(n, u);
        const uint32_t base = uint32_t(m.positions.size());
        const vec2 corners[4] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
        for (const vec2& c : corners) {
            m.positions.push_back(n + c.x * u + c.y * v);
            m.normals.push_back(n);
            m.uvs.push_back(0.5f * (c + vec2(1.0f)));
        }
        // Counter-clockwise seen from outside: (u, v, n) is right-handed.
        m.indices.insert(m.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    }
    return m;
}

TriangleMesh makeDisk(int segments) {
    TriangleMesh m;
    m.name = "disk";
    m.positions.push_back(vec3(0.0f));
    m.normals.push_back(vec3(0, 0, 1));
    m.uvs.push_back(vec2(0.0f));
    for (int i = 0; i < segments; ++i) {
        const float phi = 2.0f * kPi * i / segments;
        m.positions.push_back(vec3(std::cos(phi), std::sin(phi), 0.0f));
        m.normals.push_back(vec3(0, 0, 1));
        m.uvs.push_back(vec2(1.0f, float(i) / segments));
    }
    for (int i = 0; i < segments; ++i)
        m.indices.insert(m.indices.end(), {0u, uint32_t(1 + i), uint32_t(1 + (i + 1) % segments)});
    return m;
}

size_t openEdgeCount(const TriangleMesh& mesh) {
    // Weld: one id per distinct position (bitwise; −0 and +0 differ only in the sign bit, folded).
    auto key = [](const vec3& p) {
        auto bits = [](float f) { return f == 0.0f ? 0u : std::bit_cast<uint32_t>(f); };
        return std::array<uint32_t, 3>{bits(p.x), bits(p.y), bits(p.z)};
    };
    std::map<std::array<uint32_t, 3>, uint32_t> ids;
    std::vector<uint32_t> weld(mesh.positions.size());
    for (size_t i = 0; i < mesh.positions.size(); ++i) weld[i] = ids.emplace(key(mesh.positions[i]), uint32_t(ids.size())).first->second;
    std::map<std::pair<uint32_t, uint32_t>, int> uses;
    for (size_t t = 0; t < mesh.triangleCount(); ++t)
        for (int e = 0; e < 3; ++e) {
            uint32_t a = weld[mesh.indices[3 * t + e]], b = weld[mesh.indices[3 * t + (e + 1) % 3]];
            if (a == b) continue;  // degenerate edge
            ++uses[{std::min(a, b), std::max(a, b)}];
        }
    size_t open = 0;
    for (const auto& [edge, n] : uses) open += n != 2;
    return open;
}

}  // namespace iris
