#include "render/loader/gltf_scene.h"

#include <glm/gtc/quaternion.hpp>

namespace iris::gltf {

mat4 localMatrix(const Document& doc, int index) {
    const tinygltf::Node& n = doc.model.nodes[size_t(index)];
    const std::string path = strCat("/nodes/", index);
    if (n.matrix.size() == 16) {
        mat4 m;
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r) m[c][r] = float(n.matrix[size_t(4 * c + r)]);  // §3.5.2: column-major
        return m;
    }
    if (!n.matrix.empty()) failAtPath(doc, path + "/matrix", "needs 16 numbers, has ", n.matrix.size());
    mat4 m(1.0f);
    if (n.translation.size() == 3) m = glm::translate(m, vec3(n.translation[0], n.translation[1], n.translation[2]));
    if (n.rotation.size() == 4) {
        const glm::quat q(float(n.rotation[3]), float(n.rotation[0]), float(n.rotation[1]), float(n.rotation[2]));  // (w, x, y, z)
        if (!(std::abs(glm::length(q) - 1.0f) < 1e-2f)) failAtPath(doc, path + "/rotation", "is not a unit quaternion");
        m = m * glm::mat4_cast(glm::normalize(q));
    }
    if (n.scale.size() == 3) m = glm::scale(m, vec3(n.scale[0], n.scale[1], n.scale[2]));
    return m;
}

namespace {

/// Deeper hierarchies are refused (the walk is recursive; no real asset nests this deep).
constexpr int kMaxDepth = 256;

void visit(const Document& doc, int node, const mat4& parent, std::vector<bool>& onPath, std::vector<PlacedNode>& out,
           const std::string& from, int depth = 0) {
    if (depth > kMaxDepth) failAtPath(doc, from, "the node hierarchy is deeper than ", kMaxDepth, " levels");
    if (node < 0 || size_t(node) >= doc.model.nodes.size()) failAtPath(doc, from, "node ", node, " does not exist");
    if (onPath[size_t(node)]) failAtPath(doc, from, "node ", node, " is its own ancestor (the hierarchy must be a tree)");
    if (out.size() > 4 * doc.model.nodes.size() + 16)
        failAtPath(doc, from, "the node hierarchy visits more nodes than the file has (a node with two parents?)");
    onPath[size_t(node)] = true;
    const mat4 world = parent * localMatrix(doc, node);
    out.push_back({node, world});
    const std::vector<int>& children = doc.model.nodes[size_t(node)].children;
    for (size_t i = 0; i < children.size(); ++i) visit(doc, children[i], world, onPath, out, strCat("/nodes/", node, "/children/", i), depth + 1);
    onPath[size_t(node)] = false;
}

}  // namespace

std::vector<PlacedNode> placeNodes(const Document& doc) {
    std::vector<PlacedNode> out;
    std::vector<bool> onPath(doc.model.nodes.size(), false);
    const int s = doc.model.defaultScene >= 0 ? doc.model.defaultScene : 0;
    if (size_t(s) < doc.model.scenes.size()) {
        const std::vector<int>& roots = doc.model.scenes[size_t(s)].nodes;
        for (size_t i = 0; i < roots.size(); ++i) visit(doc, roots[i], mat4(1.0f), onPath, out, strCat("/scenes/", s, "/nodes/", i));
        return out;
    }
    if (doc.model.defaultScene >= 0) failAtPath(doc, "/scene", "scene ", s, " does not exist");
    std::vector<bool> isChild(doc.model.nodes.size(), false);
    for (const tinygltf::Node& n : doc.model.nodes)
        for (int c : n.children)
            if (c >= 0 && size_t(c) < isChild.size()) isChild[size_t(c)] = true;
    for (size_t i = 0; i < doc.model.nodes.size(); ++i)
        if (!isChild[i]) visit(doc, int(i), mat4(1.0f), onPath, out, "/nodes");
    return out;
}

}  // namespace iris::gltf
