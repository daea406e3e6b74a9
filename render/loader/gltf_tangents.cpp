#include "render/loader/gltf_tangents.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <map>
#include <tuple>
#include <utility>

#include "core/frame.h"
#include "core/memory_budget.h"
#include "core/error.h"
#include "materials/gltf_texture.h"

// Design: the tangents are a plain per-vertex attribute, and vertices whose corners need different
// tangents are split (copied) rather than the tangents being stored per corner. A per-corner
// attribute would be a new kind of MeshAttribute that every reader of mesh attributes would have to
// know; a split vertex keeps the generated tangent exactly what a file's TANGENT is (one vec4 per
// vertex, interpolated by the hit's barycentrics), and splits are rare (mirror seams that the file
// did not already split, or faces of a mesh without normals).

namespace iris::gltf {

namespace {

bool finite(const vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

/// v / |v|, or 0 when v has no direction.
vec3 unit(const vec3& v) {
    const float len = glm::length(v);
    return len > 0 && std::isfinite(len) ? v / len : vec3(0.0f);
}

/// v projected onto the plane orthogonal to the unit vector n, normalised (thesis: the tangent
/// frame of a corner lies in the tangent plane of its vertex normal); 0 when nothing is left.
vec3 projected(const vec3& v, const vec3& n) { return unit(v - n * glm::dot(n, v)); }

/// A triangle's tangent directions from its UVs.
struct FaceTangents {
    vec3 t{0.0f}, b{0.0f};  // ∂p/∂u and glTF's bitangent direction −∂p/∂v (not normalised)
    int orientation = 0;    // sign of the Jacobian of (u, 1 − v); 0: degenerate, contributes nothing
};

/// ∂p/∂u and ∂p/∂v of triangle p with UVs uv, the solution of
///   p1 − p0 = ∂p/∂u Δu1 + ∂p/∂v Δv1,   p2 − p0 = ∂p/∂u Δu2 + ∂p/∂v Δv2
/// (the thesis's per-triangle tangent and bitangent). Degenerate: zero UV or position area.
FaceTangents faceTangents(const vec3 p[3], const vec2 uv[3]) {
    const vec3 e1 = p[1] - p[0], e2 = p[2] - p[0];
    const vec2 d1 = uv[1] - uv[0], d2 = uv[2] - uv[0];
    const float det = d1.x * d2.y - d2.x * d1.y;  // twice the signed UV area
    FaceTangents f;
    if (!(std::abs(det) > 0) || !(glm::length(glm::cross(e1, e2)) > 0)) return f;
    const vec3 dpdu = (d2.y * e1 - d1.y * e2) / det;
    const vec3 dpdv = (d1.x * e2 - d2.x * e1) / det;
    if (!finite(dpdu) || !finite(dpdv)) return f;
    f.t = dpdu;
    f.b = -dpdv;  // §3.9.3: the normal texture's +Y is up in the image, towards −v (UV origin upper left)
    f.orientation = det < 0 ? 1 : -1;  // v → 1 − v flips the Jacobian's sign
    return f;
}

/// The angle of triangle p at corner k (the thesis's weight of a corner's contribution).
float cornerAngle(const vec3 p[3], int k) {
    const vec3 a = unit(p[(k + 1) % 3] - p[k]), b = unit(p[(k + 2) % 3] - p[k]);
    if (a == vec3(0.0f) || b == vec3(0.0f)) return 0.0f;
    return std::acos(std::clamp(glm::dot(a, b), -1.0f, 1.0f));
}

/// The welding key of a corner: position, normal and UV bit for bit (−0 as +0), and orientation.
struct Key {
    std::array<uint32_t, 8> bits{};
    int orientation = 0;
    bool operator<(const Key& o) const { return std::tie(bits, orientation) < std::tie(o.bits, o.orientation); }
};

uint32_t bitsOf(float f) {
    if (f == 0.0f) f = 0.0f;  // −0 welds with +0
    uint32_t u;
    std::memcpy(&u, &f, sizeof u);
    return u;
}

Key keyOf(const vec3& p, const vec3& n, const vec2& uv, int orientation) {
    return {{bitsOf(p.x), bitsOf(p.y), bitsOf(p.z), bitsOf(n.x), bitsOf(n.y), bitsOf(n.z), bitsOf(uv.x), bitsOf(uv.y)}, orientation};
}

/// The corners of one welded vertex: their angle-weighted, projected tangents and bitangents.
struct Group {
    Key key;
    vec3 n{0.0f};              // the unit vertex normal
    vec3 t{0.0f}, b{0.0f};     // Σ angle · T, Σ angle · B
};

struct Welding {
    std::vector<Group> groups;
    std::map<Key, int> ids;
    std::vector<int> cornerGroup;  // per corner (3 per triangle)

    int groupOf(const Key& key, const vec3& n) {
        const auto [it, added] = ids.emplace(key, int(groups.size()));
        if (added) groups.push_back({key, unit(n)});
        return it->second;
    }
    bool contributes(int g) const { return groups[size_t(g)].key.orientation != 0; }
};

/// UV set `set` per vertex (0: mesh.uvs, 1: kTexCoord1Attribute), or empty when the mesh has none.
std::vector<vec2> uvSet(const TriangleMesh& mesh, int set) {
    if (set == 0) return mesh.uvs;
    std::vector<vec2> out;
    const MeshAttribute* a = mesh.findAttribute(kTexCoord1Attribute);
    if (!a || a->channels != 2 || a->perFace()) return out;
    for (size_t i = 0; i + 1 < a->values.size(); i += 2) out.emplace_back(a->values[i], a->values[i + 1]);
    return out;
}

/// Every corner's welded group, and the groups' sums. A corner of a degenerate triangle (or one
/// whose tangent vanishes in its normal's plane) gets a group of orientation 0 that sums nothing.
Welding weld(const TriangleMesh& mesh, const std::vector<vec2>& uvs) {
    Welding w;
    w.cornerGroup.resize(mesh.indices.size());
    for (size_t tri = 0; tri < mesh.triangleCount(); ++tri) {
        const uint32_t* v = &mesh.indices[3 * tri];
        const vec3 p[3] = {mesh.positions[v[0]], mesh.positions[v[1]], mesh.positions[v[2]]};
        vec2 uv[3] = {vec2(0.0f), vec2(0.0f), vec2(0.0f)};
        if (!uvs.empty()) uv[0] = uvs[v[0]], uv[1] = uvs[v[1]], uv[2] = uvs[v[2]];
        const FaceTangents f = faceTangents(p, uv);
        const vec3 faceNormal = unit(glm::cross(p[1] - p[0], p[2] - p[0]));  // glTF: flat normals without NORMAL
        for (int k = 0; k < 3; ++k) {
            const vec3 n = mesh.normals.empty() ? faceNormal : mesh.normals[v[k]];
            const vec3 t = projected(f.t, unit(n)), b = projected(f.b, unit(n));
            const bool usable = f.orientation != 0 && t != vec3(0.0f);
            const int g = w.groupOf(keyOf(p[k], n, uv[k], usable ? f.orientation : 0), n);
            w.cornerGroup[3 * tri + size_t(k)] = g;
            if (!usable) continue;
            const float angle = cornerAngle(p, k);
            w.groups[size_t(g)].t += angle * t;
            w.groups[size_t(g)].b += angle * b;
        }
    }
    return w;
}

/// Appends a copy of vertex v (position, normal, uv and every per-vertex attribute); its index.
uint32_t copyVertex(TriangleMesh& mesh, uint32_t v) {
    mesh.positions.push_back(mesh.positions[v]);
    if (!mesh.normals.empty()) mesh.normals.push_back(mesh.normals[v]);
    if (!mesh.uvs.empty()) mesh.uvs.push_back(mesh.uvs[v]);
    for (MeshAttribute& a : mesh.attributes) {
        if (a.perFace()) continue;
        const size_t c = size_t(a.channels);
        for (size_t k = 0; k < c; ++k) a.values.push_back(a.values[v * c + k]);
    }
    return uint32_t(mesh.positions.size() - 1);
}

/// Each vertex's group: the first contributing group among its corners; corners of another
/// contributing group move to a copy of the vertex (one copy per (vertex, group)). Corners that
/// contribute nothing stay and take the vertex's group; a vertex with only such corners takes the
/// first one's (−1: a vertex no triangle uses).
std::vector<int> splitVertices(TriangleMesh& mesh, const Welding& w) {
    std::vector<int> vertexGroup(mesh.positions.size(), -1);
    std::map<std::pair<uint32_t, int>, uint32_t> copies;
    for (size_t c = 0; c < mesh.indices.size(); ++c) {
        const uint32_t v = mesh.indices[c];
        const int g = w.cornerGroup[c];
        if (!w.contributes(g)) continue;
        if (vertexGroup[v] < 0) vertexGroup[v] = g;
        if (vertexGroup[v] == g) continue;
        const auto [it, added] = copies.emplace(std::make_pair(v, g), 0u);
        if (added) {
            it->second = copyVertex(mesh, v);
            vertexGroup.push_back(g);
        }
        mesh.indices[c] = it->second;
    }
    for (size_t c = 0; c < mesh.indices.size(); ++c)
        if (int& g = vertexGroup[mesh.indices[c]]; g < 0) g = w.cornerGroup[c];
    return vertexGroup;
}

/// A tangent orthogonal to n, the same for the same n (Duff et al.'s basis), with w = 1.
vec4 fallbackTangent(const vec3& n) { return vec4(n == vec3(0.0f) ? vec3(1, 0, 0) : Frame::fromNormal(n).s, 1.0f); }

/// Group g's tangent: T = normalize(Σ T), w = sign(dot(N × T, Σ B)) (§3.7.2.1: bitangent =
/// cross(normal, tangent.xyz) · w). A group that sums nothing borrows the welded group of the same
/// position, normal and UV with orientation +1, else −1, else falls back.
vec4 groupTangent(const Welding& w, int g) {
    const Group& group = w.groups[size_t(g)];
    if (!w.contributes(g)) {
        for (const int o : {1, -1}) {
            Key k = group.key;
            k.orientation = o;
            if (const auto it = w.ids.find(k); it != w.ids.end()) return groupTangent(w, it->second);
        }
        return fallbackTangent(group.n);
    }
    const vec3 t = unit(group.t);
    if (t == vec3(0.0f)) return fallbackTangent(group.n);  // contributions that cancel
    const float s = glm::dot(glm::cross(group.n, t), group.b);
    return vec4(t, s > 0 ? 1.0f : s < 0 ? -1.0f : float(group.key.orientation));
}

}  // namespace

void generateTangents(TriangleMesh& mesh, int texCoord) {
    const Welding w = weld(mesh, uvSet(mesh, texCoord));
    const std::vector<int> vertexGroup = splitVertices(mesh, w);
    chargeMemory(uint64_t(vertexGroup.size()) * 4 * sizeof(float), strCat(mesh.name, ": generated tangents"));
    MeshAttribute a;
    a.name = kTangentAttribute;
    a.channels = 4;
    a.values.reserve(4 * vertexGroup.size());
    for (size_t v = 0; v < vertexGroup.size(); ++v) {
        const vec4 t = vertexGroup[v] >= 0 ? groupTangent(w, vertexGroup[v])
                                           : fallbackTangent(mesh.normals.empty() ? vec3(0.0f) : unit(mesh.normals[v]));
        a.values.insert(a.values.end(), {t.x, t.y, t.z, t.w});
    }
    mesh.attributes.push_back(std::move(a));
}

}  // namespace iris::gltf
