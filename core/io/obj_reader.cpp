#include "core/io/obj_reader.h"

#include <charconv>
#include <unordered_map>

#include "core/error.h"
#include "core/input_file.h"
#include "core/memory_budget.h"

namespace iris {
namespace {

struct Cursor {
    const char* p;
    const char* end;
    void skipSpace() {
        while (p < end && (*p == ' ' || *p == '\t' || *p == '\r')) ++p;
    }
    bool atEnd() {
        skipSpace();
        return p >= end;
    }
};

struct CornerKey {
    int64_t v, t, n;
    bool operator==(const CornerKey& o) const { return v == o.v && t == o.t && n == o.n; }
};
struct CornerHash {
    size_t operator()(const CornerKey& k) const {
        return size_t(k.v) * 73856093u ^ size_t(k.t + 1) * 19349663u ^ size_t(k.n + 1) * 83492791u;
    }
};

class ObjParser {
public:
    explicit ObjParser(const std::string& name) : name_(name) {}

    TriangleMesh parse(const std::string& text) {
        const char* p = text.data();
        const char* end = p + text.size();
        while (p < end) {
            ++line_;
            const char* eol = p;
            while (eol < end && *eol != '\n') ++eol;
            parseLine(Cursor{p, eol});
            p = eol < end ? eol + 1 : end;
        }
        return finish();
    }

private:
    [[noreturn]] void error(const std::string& msg) const { fail(name_, ":", line_, ": ", msg); }

    float number(Cursor& c) {
        c.skipSpace();
        if (c.p < c.end && *c.p == '+') ++c.p;
        float v = 0.0f;
        const auto [ptr, ec] = std::from_chars(c.p, c.end, v);
        if (ec != std::errc() || ptr == c.p) error("expected a number");
        c.p = ptr;
        return v;
    }

    /// One index of a face corner: 1-based, negative = relative to the current count.
    int64_t index(Cursor& c, size_t count, const char* what) {
        int64_t i = 0;
        const auto [ptr, ec] = std::from_chars(c.p, c.end, i);
        if (ec != std::errc() || ptr == c.p) error(strCat("malformed ", what, " index in face"));
        c.p = ptr;
        const int64_t resolved = i > 0 ? i - 1 : int64_t(count) + i;
        if (i == 0 || resolved < 0 || resolved >= int64_t(count))
            error(strCat(what, " index ", i, " out of range (", count, " defined so far)"));
        return resolved;
    }

    void parseLine(Cursor c) {
        c.skipSpace();
        const char* kw = c.p;
        while (c.p < c.end && *c.p != ' ' && *c.p != '\t' && *c.p != '\r') ++c.p;
        const std::string_view key(kw, size_t(c.p - kw));
        if (key.empty() || key[0] == '#') return;
        if (key == "v") {
            vec3 v;
            for (int i = 0; i < 3; ++i) v[i] = number(c);
            positions_.push_back(v);  // an optional w or vertex colour is ignored
        } else if (key == "vn") {
            vec3 n;
            for (int i = 0; i < 3; ++i) n[i] = number(c);
            normals_.push_back(n);
        } else if (key == "vt") {
            vec2 t;
            t.x = number(c);
            t.y = c.atEnd() ? 0.0f : number(c);
            uvs_.push_back(vec2(t.x, 1.0f - t.y));  // Mitsuba's OBJ convention
        } else if (key == "f") {
            face(c);
        }
        // o, g, s, usemtl, mtllib, l, p, ...: ignored
    }

    void face(Cursor& c) {
        corners_.clear();
        while (!c.atEnd()) {
            CornerKey k{index(c, positions_.size(), "vertex"), -1, -1};
            if (c.p < c.end && *c.p == '/') {
                ++c.p;
                if (c.p < c.end && *c.p != '/') k.t = index(c, uvs_.size(), "texture coordinate");
                if (c.p < c.end && *c.p == '/') {
                    ++c.p;
                    k.n = index(c, normals_.size(), "normal");
                }
            }
            if (c.p < c.end && *c.p != ' ' && *c.p != '\t' && *c.p != '\r') error("malformed face corner");
            corners_.push_back(vertexFor(k));
        }
        if (corners_.size() < 3) error("a face needs at least 3 vertices");
        for (size_t i = 1; i + 1 < corners_.size(); ++i)  // fan triangulation
            indices_.insert(indices_.end(), {corners_[0], corners_[i], corners_[i + 1]});
    }

    uint32_t vertexFor(const CornerKey& k) {
        const auto [it, inserted] = map_.try_emplace(k, uint32_t(keys_.size()));
        if (inserted) {
            if (keys_.size() >= UINT32_MAX) error("too many vertices");
            keys_.push_back(k);
        }
        return it->second;
    }

    TriangleMesh finish() {
        TriangleMesh m;
        m.name = name_;
        bool allNormals = !keys_.empty(), anyUV = false;
        for (const CornerKey& k : keys_) {
            allNormals = allNormals && k.n >= 0;
            anyUV = anyUV || k.t >= 0;
        }
        m.positions.reserve(keys_.size());
        for (const CornerKey& k : keys_) {
            m.positions.push_back(positions_[size_t(k.v)]);
            if (allNormals) m.normals.push_back(normals_[size_t(k.n)]);
            if (anyUV) m.uvs.push_back(k.t >= 0 ? uvs_[size_t(k.t)] : vec2(0.0f));
        }
        m.indices = std::move(indices_);
        if (m.indices.empty()) fail(name_, ": the OBJ file contains no faces");
        m.validate();
        return m;
    }

    std::string name_;
    int line_ = 0;
    std::vector<vec3> positions_, normals_;
    std::vector<vec2> uvs_;
    std::vector<uint32_t> indices_, corners_;
    std::vector<CornerKey> keys_;
    std::unordered_map<CornerKey, uint32_t, CornerHash> map_;
};

}  // namespace

TriangleMesh parseObj(const std::string& text, const std::string& name) { return ObjParser(name).parse(text); }

// OBJ has no header that counts its vertices and faces: the file is charged before it is read, the
// mesh (at most a small multiple of the file) when parsed, before the scene keeps it.
TriangleMesh readObj(const std::string& path) {
    TriangleMesh m = parseObj(readInputFile(path, "OBJ file"), path);
    const uint64_t held = m.positions.size() * sizeof(vec3) + m.normals.size() * sizeof(vec3) +
                          m.uvs.size() * sizeof(vec2) + m.indices.size() * sizeof(uint32_t);
    chargeMemory(held, strCat(path, ": ", m.positions.size(), " vertices and ", m.triangleCount(), " triangles"));
    return m;
}

}  // namespace iris
