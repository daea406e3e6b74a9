#include "core/io/ply_reader.h"

#include <algorithm>
#include <bit>
#include <charconv>
#include <cstring>
#include "core/error.h"
#include "core/input_file.h"
#include "core/memory_budget.h"
#include "core/xml/xml_values.h"
#include "core/srgb_transfer.h"

namespace iris {
namespace {

enum class ScalarType { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

int sizeOf(ScalarType t) {
    switch (t) {
        case ScalarType::Int8: case ScalarType::UInt8: return 1;
        case ScalarType::Int16: case ScalarType::UInt16: return 2;
        case ScalarType::Int32: case ScalarType::UInt32: case ScalarType::Float32: return 4;
        case ScalarType::Float64: return 8;
    }
    return 1;
}

bool isInteger(ScalarType t) { return t != ScalarType::Float32 && t != ScalarType::Float64; }

/// The largest value of an integer type (the 1 of a normalised integer).
double integerMax(ScalarType t) {
    switch (t) {
        case ScalarType::Int8: return 127.0;
        case ScalarType::UInt8: return 255.0;
        case ScalarType::Int16: return 32767.0;
        case ScalarType::UInt16: return 65535.0;
        case ScalarType::Int32: return 2147483647.0;
        case ScalarType::UInt32: return 4294967295.0;
        default: return 1.0;
    }
}

bool parseType(const std::string& s, ScalarType& t) {
    static const struct { const char* name; ScalarType type; } table[] = {
        {"char", ScalarType::Int8},     {"int8", ScalarType::Int8},       {"uchar", ScalarType::UInt8},
        {"uint8", ScalarType::UInt8},   {"short", ScalarType::Int16},     {"int16", ScalarType::Int16},
        {"ushort", ScalarType::UInt16}, {"uint16", ScalarType::UInt16},   {"int", ScalarType::Int32},
        {"int32", ScalarType::Int32},   {"uint", ScalarType::UInt32},     {"uint32", ScalarType::UInt32},
        {"float", ScalarType::Float32}, {"float32", ScalarType::Float32}, {"double", ScalarType::Float64},
        {"float64", ScalarType::Float64}};
    for (const auto& e : table)
        if (s == e.name) {
            t = e.type;
            return true;
        }
    return false;
}

struct Property {
    std::string name;
    ScalarType type = ScalarType::Float32;
    bool isList = false;
    ScalarType countType = ScalarType::UInt8;
};

struct Element {
    std::string name;
    uint64_t count = 0;
    std::vector<Property> props;
};

enum class Format { Ascii, BinaryLE, BinaryBE };

/// An extra property group of an element kept as a mesh attribute: its name and, per channel,
/// the index of the property that holds it.
struct AttributeLayout {
    std::string name;
    std::vector<int> props;
};

/// The mesh attributes of an element's scalar properties other than `reserved`, named as Mitsuba
/// 3's PLY loader names them (src/shapes/ply.h, find_other_fields): r g b (or red green blue) →
/// `<prefix>color` (3 channels; an alpha is dropped: Mitsuba keeps a 4th channel, which its
/// mesh_attribute cannot evaluate); consecutive `P_x P_y P_z`, `P_r P_g P_b` (→ `<prefix>P_color`),
/// `P_0 P_1 P_2`, `P_1 P_2 P_3` → `<prefix>P` with up to 4 channels. iris also keeps every other
/// scalar property `q` as a 1-channel `<prefix>q` (Mitsuba ignores them with a warning); a name
/// seen before is skipped.
std::vector<AttributeLayout> attributeLayouts(const Element& e, const std::string& prefix,
                                              std::vector<std::string> reserved) {
    std::vector<AttributeLayout> out;
    auto index = [&](const std::string& n) {
        for (size_t i = 0; i < e.props.size(); ++i)
            if (!e.props[i].isList && e.props[i].name == n) return int(i);
        return -1;
    };
    for (const auto& rgb : {std::vector<std::string>{"r", "g", "b"}, std::vector<std::string>{"red", "green", "blue"}}) {
        AttributeLayout c{prefix + "color", {index(rgb[0]), index(rgb[1]), index(rgb[2])}};
        if (out.empty() && c.props[0] >= 0 && c.props[1] >= 0 && c.props[2] >= 0) out.push_back(c);
    }
    reserved.insert(reserved.end(), {"r", "g", "b", "a", "red", "green", "blue", "alpha"});
    static const char* const kSequences[4] = {"xyzw", "rgba", "0123", "1234"};  // Mitsuba's postfix categories
    AttributeLayout group;
    std::string groupStem;
    int sequence = -1;  // the postfix category of the group being read, or -1
    auto add = [&](AttributeLayout a) {
        for (const AttributeLayout& o : out)
            if (o.name == a.name) return;
        out.push_back(std::move(a));
    };
    auto flush = [&] {
        if (sequence >= 0) add(group);
        sequence = -1;
    };
    for (int i = 0; i < int(e.props.size()); ++i) {
        const Property& p = e.props[size_t(i)];
        if (p.isList || std::find(reserved.begin(), reserved.end(), p.name) != reserved.end()) continue;
        const size_t us = p.name.find_last_of('_');
        const bool postfixed = us != std::string::npos && us > 0 && us + 2 == p.name.size();
        const std::string stem = postfixed ? p.name.substr(0, us) : p.name;
        const char last = p.name.back();
        if (sequence >= 0 && postfixed && stem == groupStem && group.props.size() < 4 && kSequences[sequence][group.props.size()] == last) {
            group.props.push_back(i);
            continue;
        }
        flush();
        for (int k = 0; k < 4 && postfixed; ++k)
            if (kSequences[k][0] == last) sequence = k;
        groupStem = stem;
        if (sequence >= 0) group = {prefix + stem + (sequence == 1 ? "_color" : ""), {i}};
        else add({prefix + p.name, {i}});
    }
    flush();
    return out;
}

class PlyParser {
public:
    PlyParser(const std::string& data, const std::string& name) : data_(data), name_(name) {}

    TriangleMesh parse() {
        parseHeader();
        TriangleMesh m;
        m.name = name_;
        for (const Element& e : elements_) {
            if (e.name == "vertex") readVertices(e, m);
            else if (e.name == "face") readFaces(e, m);
            else skipElement(e);
        }
        if (m.indices.empty()) fail(name_, ": the PLY file contains no faces");
        m.validate();
        return m;
    }

private:
    [[noreturn]] void error(const std::string& msg) const {
        if (format_ == Format::Ascii || inHeader_) fail(name_, ":", line_, ": ", msg);
        fail(name_, ": ", msg, " (at byte ", pos_, ")");
    }

    // ---- header ----
    std::string headerLine() {
        if (pos_ >= data_.size()) error("unexpected end of file in header (missing end_header)");
        const size_t eol = data_.find('\n', pos_);
        const size_t stop = eol == std::string::npos ? data_.size() : eol;
        std::string l = data_.substr(pos_, stop - pos_);
        if (!l.empty() && l.back() == '\r') l.pop_back();
        pos_ = stop + (eol == std::string::npos ? 0 : 1);
        ++line_;
        return l;
    }

    void parseHeader() {
        if (headerLine() != "ply") error("not a PLY file (missing 'ply' magic)");
        bool haveFormat = false;
        for (;;) {
            std::istringstream ls(headerLine());
            std::string kw;
            ls >> kw;
            if (kw == "end_header") break;
            if (kw.empty() || kw == "comment" || kw == "obj_info") continue;
            if (kw == "format") {
                std::string f, version;
                ls >> f >> version;
                if (f == "ascii") format_ = Format::Ascii;
                else if (f == "binary_little_endian") format_ = Format::BinaryLE;
                else if (f == "binary_big_endian") format_ = Format::BinaryBE;
                else error("unknown PLY format '" + f + "'");
                haveFormat = true;
            } else if (kw == "element") {
                Element e;
                std::string count;
                ls >> e.name >> count;
                const auto [p, ec] = std::from_chars(count.data(), count.data() + count.size(), e.count);
                if (e.name.empty() || ec != std::errc() || p != count.data() + count.size())
                    error("malformed element declaration");
                elements_.push_back(e);
            } else if (kw == "property") {
                if (elements_.empty()) error("property before any element");
                Property p;
                std::string t;
                ls >> t;
                if (t == "list") {
                    std::string ct, it;
                    ls >> ct >> it >> p.name;
                    p.isList = true;
                    if (!parseType(ct, p.countType) || !isInteger(p.countType)) error("bad list count type '" + ct + "'");
                    if (!parseType(it, p.type)) error("unknown property type '" + it + "'");
                } else {
                    ls >> p.name;
                    if (!parseType(t, p.type)) error("unknown property type '" + t + "'");
                }
                if (p.name.empty()) error("property without a name");
                elements_.back().props.push_back(p);
            } else {
                error("unknown header keyword '" + kw + "'");
            }
        }
        if (!haveFormat) error("missing format line");
        inHeader_ = false;
        ++line_;  // the body starts on the next line
        // Every element must fit in what is left of the file: at least 1 byte per scalar (binary) or
        // 2 characters ("0 ") per value (ASCII). This bounds all allocations by the file size.
        const uint64_t left = data_.size() - pos_;
        for (const Element& e : elements_) {
            uint64_t minSize = 0;
            for (const Property& p : e.props)
                minSize += format_ == Format::Ascii ? 2 : uint64_t(p.isList ? sizeOf(p.countType) : sizeOf(p.type));
            if (minSize == 0 && e.count > 0 && e.props.empty()) continue;
            if (minSize > 0 && e.count > left / minSize)
                error(strCat("element '", e.name, "' count ", e.count, " exceeds what the file can hold"));
        }
    }

    // ---- body scalars ----
    void skipAsciiSpace() {
        while (pos_ < data_.size()) {
            const char c = data_[pos_];
            if (c == '\n') ++line_;
            else if (c != ' ' && c != '\t' && c != '\r') break;
            ++pos_;
        }
    }

    double readScalar(ScalarType t) {
        if (format_ == Format::Ascii) {
            skipAsciiSpace();
            if (pos_ >= data_.size()) error("unexpected end of file");
            const char* b = data_.data() + pos_;
            const char* e = data_.data() + data_.size();
            double v = 0;
            if (*b == '+') ++b;
            const auto [p, ec] = std::from_chars(b, e, v);
            if (ec != std::errc() || p == b) error("expected a number");
            pos_ = size_t(p - data_.data());
            return v;
        }
        const int n = sizeOf(t);
        if (pos_ + size_t(n) > data_.size()) error("unexpected end of file (truncated binary data)");
        unsigned char b[8];
        std::memcpy(b, data_.data() + pos_, size_t(n));
        pos_ += size_t(n);
        const bool swap = (format_ == Format::BinaryBE) == (std::endian::native == std::endian::little);
        if (swap) std::reverse(b, b + n);
        switch (t) {
            case ScalarType::Int8: { int8_t v; std::memcpy(&v, b, 1); return v; }
            case ScalarType::UInt8: return b[0];
            case ScalarType::Int16: { int16_t v; std::memcpy(&v, b, 2); return v; }
            case ScalarType::UInt16: { uint16_t v; std::memcpy(&v, b, 2); return v; }
            case ScalarType::Int32: { int32_t v; std::memcpy(&v, b, 4); return v; }
            case ScalarType::UInt32: { uint32_t v; std::memcpy(&v, b, 4); return v; }
            case ScalarType::Float32: { float v; std::memcpy(&v, b, 4); return v; }
            case ScalarType::Float64: { double v; std::memcpy(&v, b, 8); return v; }
        }
        return 0;
    }

    uint64_t readCount(const Property& p) {
        const double c = readScalar(p.countType);
        if (!(c >= 0) || c != std::floor(c)) error("invalid list length");
        if (c > double(data_.size() - pos_)) error("list length exceeds the file size");
        return uint64_t(c);
    }

    void skipProperty(const Property& p) {
        const uint64_t n = p.isList ? readCount(p) : 1;
        for (uint64_t i = 0; i < n; ++i) readScalar(p.type);
    }

    void skipElement(const Element& e) {
        if (e.props.empty()) return;  // nothing stored, whatever the count says
        for (uint64_t i = 0; i < e.count; ++i)
            for (const Property& p : e.props) skipProperty(p);
    }

    // ---- mesh attributes ----
    /// A property's value as a mesh attribute holds it: integers divided by their type's maximum
    /// and decoded from sRGB, floats as stored. (Mitsuba 3 flags every integer PLY property
    /// Normalized | Gamma, src/shapes/ply.h parse_ply_header; its StructConverter, src/core/struct.cpp
    /// linearize, divides by the maximum and then applies the inverse sRGB curve: a uchar colour
    /// 255·c_srgb becomes linear.)
    static float attributeValue(double v, ScalarType t) {
        return isInteger(t) ? srgbToLinear(float(v / integerMax(t))) : float(v);
    }

    static std::vector<MeshAttribute> emptyAttributes(const std::vector<AttributeLayout>& layouts, uint64_t count) {
        std::vector<MeshAttribute> out;
        for (const AttributeLayout& l : layouts) {
            out.push_back({l.name, int(l.props.size()), {}});
            out.back().values.reserve(size_t(count) * l.props.size());
        }
        return out;
    }

    static uint64_t attributeBytes(const std::vector<AttributeLayout>& layouts) {
        uint64_t n = 0;
        for (const AttributeLayout& l : layouts) n += l.props.size() * sizeof(float);
        return n;
    }

    /// Append one element's values, `times` times (a polygon's face values to each of its triangles).
    static void appendAttributes(const Element& e, const std::vector<AttributeLayout>& layouts,
                                 const std::vector<double>& values, size_t times, std::vector<MeshAttribute>& attrs) {
        for (size_t a = 0; a < layouts.size(); ++a)
            for (size_t t = 0; t < times; ++t)
                for (int i : layouts[a].props) attrs[a].values.push_back(attributeValue(values[size_t(i)], e.props[size_t(i)].type));
    }

    static void moveAttributes(std::vector<MeshAttribute>& from, TriangleMesh& m) {
        for (MeshAttribute& a : from) m.attributes.push_back(std::move(a));
    }

    // ---- vertices and faces ----
    void readVertices(const Element& e, TriangleMesh& m) {
        if (!m.positions.empty()) error("more than one vertex element");
        int pos[3] = {-1, -1, -1}, nrm[3] = {-1, -1, -1}, uv[2] = {-1, -1};
        for (int i = 0; i < int(e.props.size()); ++i) {
            const Property& p = e.props[size_t(i)];
            if (p.isList) continue;
            const std::string& n = p.name;
            if (n == "x") pos[0] = i;
            else if (n == "y") pos[1] = i;
            else if (n == "z") pos[2] = i;
            else if (n == "nx") nrm[0] = i;
            else if (n == "ny") nrm[1] = i;
            else if (n == "nz") nrm[2] = i;
            else if (n == "u" || n == "s" || n == "texture_u" || n == "texture_s") uv[0] = i;
            else if (n == "v" || n == "t" || n == "texture_v" || n == "texture_t") uv[1] = i;
        }
        if (pos[0] < 0 || pos[1] < 0 || pos[2] < 0) error("vertex element lacks x, y or z");
        const bool hasN = nrm[0] >= 0 && nrm[1] >= 0 && nrm[2] >= 0;
        const bool hasUV = uv[0] >= 0 && uv[1] >= 0;
        const std::vector<AttributeLayout> layouts = attributeLayouts(
            e, "vertex_", {"x", "y", "z", "nx", "ny", "nz", "u", "v", "s", "t", "texture_u", "texture_v", "texture_s", "texture_t"});
        const uint64_t perVertex = sizeof(vec3) * (hasN ? 2 : 1) + (hasUV ? sizeof(vec2) : 0) + attributeBytes(layouts);
        chargeMemory(e.count * perVertex, strCat(name_, ": ", e.count, " vertices (PLY header)"));
        m.positions.resize(e.count);
        if (hasN) m.normals.resize(e.count);
        if (hasUV) m.uvs.resize(e.count);
        std::vector<MeshAttribute> attrs = emptyAttributes(layouts, e.count);
        std::vector<double> values(e.props.size());
        for (uint64_t v = 0; v < e.count; ++v) {
            for (size_t i = 0; i < e.props.size(); ++i) {
                if (e.props[i].isList) skipProperty(e.props[i]);
                else values[i] = readScalar(e.props[i].type);
            }
            for (int k = 0; k < 3; ++k) m.positions[v][k] = float(values[size_t(pos[k])]);
            if (hasN)
                for (int k = 0; k < 3; ++k) m.normals[v][k] = float(values[size_t(nrm[k])]);
            if (hasUV) m.uvs[v] = vec2(float(values[size_t(uv[0])]), float(values[size_t(uv[1])]));
            appendAttributes(e, layouts, values, 1, attrs);
        }
        moveAttributes(attrs, m);
    }

    void readFaces(const Element& e, TriangleMesh& m) {
        int listIndex = -1;
        for (int i = 0; i < int(e.props.size()); ++i) {
            const Property& p = e.props[size_t(i)];
            if (p.isList && (p.name == "vertex_indices" || p.name == "vertex_index")) listIndex = i;
        }
        if (listIndex < 0) error("face element lacks a vertex_indices list");
        if (!isInteger(e.props[size_t(listIndex)].type)) error("face indices must be integers");
        const std::vector<AttributeLayout> layouts = attributeLayouts(e, "face_", {});
        // At least one triangle per face; larger polygons are fanned into more as they are read.
        chargeMemory(e.count * (3 * sizeof(uint32_t) + attributeBytes(layouts)),
                     strCat(name_, ": ", e.count, " faces (PLY header)"));
        std::vector<MeshAttribute> attrs = emptyAttributes(layouts, e.count);
        std::vector<double> values(e.props.size());
        std::vector<uint32_t> poly;
        for (uint64_t f = 0; f < e.count; ++f) {
            for (int i = 0; i < int(e.props.size()); ++i) {
                const Property& p = e.props[size_t(i)];
                if (i == listIndex) readPolygon(p, f, poly);
                else if (p.isList) skipProperty(p);
                else values[size_t(i)] = readScalar(p.type);
            }
            for (size_t k = 1; k + 1 < poly.size(); ++k)  // fan triangulation
                m.indices.insert(m.indices.end(), {poly[0], poly[k], poly[k + 1]});
            appendAttributes(e, layouts, values, poly.size() - 2, attrs);  // face values on each of its triangles
        }
        moveAttributes(attrs, m);
    }

    void readPolygon(const Property& p, uint64_t f, std::vector<uint32_t>& poly) {
        const uint64_t n = readCount(p);
        poly.clear();
        for (uint64_t k = 0; k < n; ++k) {
            const double idx = readScalar(p.type);
            if (!(idx >= 0) || idx > double(UINT32_MAX) || idx != std::floor(idx)) error("invalid vertex index");
            poly.push_back(uint32_t(idx));
        }
        if (n < 3) error(strCat("face ", f, " has ", n, " vertices (at least 3 needed)"));
    }

    const std::string& data_;
    std::string name_;
    size_t pos_ = 0;
    int line_ = 0;
    bool inHeader_ = true;
    Format format_ = Format::Ascii;
    std::vector<Element> elements_;
};

}  // namespace

TriangleMesh parsePly(const std::string& data, const std::string& name) { return PlyParser(data, name).parse(); }

TriangleMesh readPly(const std::string& path) { return parsePly(readInputFile(path, "PLY file"), path); }

}  // namespace iris
