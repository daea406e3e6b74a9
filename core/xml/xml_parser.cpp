#include "core/xml/xml_parser.h"

#include <algorithm>
#include <filesystem>
#include <set>
#include <sstream>

#include <pugixml.hpp>

#include "core/input_file.h"
#include "core/memory_budget.h"
#include "core/xml/xml_values.h"
#include "core/transforms.h"

namespace iris {
namespace {

namespace fs = std::filesystem;

constexpr int kMaxIncludeDepth = 32;
constexpr int kMaxNesting = 64;
/// What parsing holds per byte of XML, charged to the memory budget before a document is parsed:
/// pugixml's copy of the text and its nodes, the line table and the Properties trees. Measured as
/// peak resident memory over the text's size: 13.5 for 10^6 spheres sharing a bsdf (130 MB of XML,
/// 1.76 GB), 14.7 for 10^5 spheres each with a transform and a bsdf (18 MB, 266 MB); issue 38 item 5.
constexpr uint64_t kParsedBytesPerTextByte = 16;

const std::set<std::string> kObjectTags = {"bsdf",    "texture", "emitter", "shape",  "sensor", "integrator",
                                           "sampler", "film",    "rfilter", "medium", "phase", "volume"};
const std::set<std::string> kValueTags = {"float", "integer", "boolean", "string",    "point",    "vector",
                                          "rgb",   "srgb",    "color",   "spectrum", "blackbody", "transform"};

/// One XML file being read (a stack of them while includes are processed).
struct FileContext {
    std::string name;                 // for messages
    fs::path dir;                     // for relative paths
    std::vector<ptrdiff_t> lineStarts;
    int major = 3;                    // scene format major version (0 = Mitsuba 0.6)

    int lineOf(ptrdiff_t offset) const {
        if (offset < 0) return 0;
        return int(std::upper_bound(lineStarts.begin(), lineStarts.end(), offset) - lineStarts.begin());
    }
};

class XmlParser {
public:
    explicit XmlParser(const std::map<std::string, std::string>& defines) : params_(defines), defines_(defines) {}

    ParsedScene parseFile(const std::string& path) {
        scene_.sourceFile = path;
        includeFile(path, SourceLocation{});
        resolveRefs();
        checkDefinesUsed(path);
        return std::move(scene_);
    }

    ParsedScene parseString(const std::string& xml, const std::string& baseDir) {
        scene_.sourceFile = "<string>";
        parseDocument(xml, "<string>", fs::path(baseDir.empty() ? "." : baseDir));
        resolveRefs();
        checkDefinesUsed("<string>");
        return std::move(scene_);
    }

private:
    /// A command-line override (-D name=value) that the scene neither declares with <default> nor
    /// uses as $name would silently change nothing: report it.
    void checkDefinesUsed(const std::string& file) const {
        for (const auto& [name, value] : defines_)
            if (!declared_.count(name) && !used_.count(name))
                failAt(SourceLocation{file, 0}, "-D ", name, "=", value, ": the scene has no parameter '", name,
                       "' (no <default name=\"", name, "\"> and no $", name, ")");
    }

    // ---------------------------------------------------------------- files and documents
    void includeFile(const std::string& path, const SourceLocation& from) {
        std::error_code ec;
        const fs::path abs = fs::weakly_canonical(fs::absolute(path, ec), ec);
        const std::string key = abs.string();
        if (std::find(openFiles_.begin(), openFiles_.end(), key) != openFiles_.end())
            failAt(from, "recursive include of '", path, "'");
        if (int(openFiles_.size()) >= kMaxIncludeDepth) failAt(from, "includes nested too deeply (limit ", kMaxIncludeDepth, ")");
        // The checks of core/input_file.h: a regular file within kMaxSceneFileBytes (an <include>
        // of /dev/zero grew one buffer without end, issue 38); an include's error gets its line.
        const std::string text = from.file.empty() ? readInputFile(path, "scene file", kMaxSceneFileBytes)
                                                   : withLocation(from, [&] { return readInputFile(path, "included file", kMaxSceneFileBytes); });
        openFiles_.push_back(key);
        parseDocument(text, path, abs.parent_path());
        openFiles_.pop_back();
    }

    void parseDocument(const std::string& text, const std::string& name, const fs::path& dir) {
        chargeMemory(uint64_t(text.size()) * kParsedBytesPerTextByte, strCat(name, ": parsing ", formatBytes(text.size()), " of scene XML"));
        FileContext ctx;
        ctx.name = name;
        ctx.dir = dir;
        ctx.lineStarts.push_back(0);
        for (size_t i = 0; i < text.size(); ++i)
            if (text[i] == '\n') ctx.lineStarts.push_back(ptrdiff_t(i + 1));
        files_.push_back(ctx);

        pugi::xml_document doc;
        const pugi::xml_parse_result r = doc.load_buffer(text.data(), text.size(), pugi::parse_default, pugi::encoding_utf8);
        if (!r) failAt(SourceLocation{name, files_.back().lineOf(r.offset)}, "XML parse error: ", r.description());
        const pugi::xml_node root = doc.document_element();
        if (!root || std::string(root.name()) != "scene") failAt(loc(root), "the root element must be <scene>");
        checkAttributes(root, {"version"});
        const pugi::xml_attribute ver = root.attribute("version");
        if (!ver) failAt(loc(root), "<scene> lacks the version attribute (e.g. version=\"3.0.0\")");
        const std::string v = attr(root, "version");
        const size_t dot = v.find('.');
        const int major = int(parseIntValue(v.substr(0, dot), loc(root)));
        if (major != 0 && major != 2 && major != 3)
            failAt(loc(root), "unsupported scene version '", v, "' (supported: 0.6.x, 2.x, 3.x)");
        files_.back().major = major;

        for (pugi::xml_node n = root.first_child(); n; n = n.next_sibling()) {
            if (n.type() != pugi::node_element) continue;
            sceneChild(n);
        }
        files_.pop_back();
    }

    // ---------------------------------------------------------------- helpers
    SourceLocation loc(const pugi::xml_node& n) const {
        const FileContext& f = files_.back();
        return SourceLocation{f.name, n ? f.lineOf(n.offset_debug()) : 0};
    }

    void checkAttributes(const pugi::xml_node& n, std::initializer_list<const char*> allowed) const {
        for (pugi::xml_attribute a = n.first_attribute(); a; a = a.next_attribute()) {
            const std::string an = a.name();
            if (std::none_of(allowed.begin(), allowed.end(), [&](const char* s) { return an == s; })) {
                std::string list;
                for (const char* s : allowed) list += (list.empty() ? "" : ", ") + std::string(s);
                failAt(loc(n), "unexpected attribute '", an, "' on <", n.name(), "> (allowed: ", list, ")");
            }
        }
    }

    /// Attribute value with $name parameters substituted.
    std::string attr(const pugi::xml_node& n, const char* name) const {
        const std::string raw = n.attribute(name).value();
        std::string out;
        for (size_t i = 0; i < raw.size(); ++i) {
            if (raw[i] != '$') {
                out += raw[i];
                continue;
            }
            size_t j = i + 1;
            while (j < raw.size() && (std::isalnum(static_cast<unsigned char>(raw[j])) || raw[j] == '_')) ++j;
            const std::string key = raw.substr(i + 1, j - i - 1);
            if (key.empty()) failAt(loc(n), "'$' without a parameter name in '", raw, "'");
            used_.insert(key);
            const auto it = params_.find(key);
            if (it == params_.end())
                failAt(loc(n), "undefined parameter '$", key, "' (define it with <default name=\"", key,
                       "\" value=\"...\"/> or -D ", key, "=...)");
            out += it->second;
            i = j - 1;
        }
        return out;
    }

    std::string requiredAttr(const pugi::xml_node& n, const char* name) const {
        if (!n.attribute(name)) failAt(loc(n), "<", n.name(), "> lacks the '", name, "' attribute");
        return attr(n, name);
    }

    /// Parameter name as written (a version 0.x file's camelCase names are upgraded after parsing,
    /// render/loader/scene_upgrade.h).
    std::string paramName(const pugi::xml_node& n) const {
        const std::string name = requiredAttr(n, "name");
        if (name.empty()) failAt(loc(n), "empty parameter name");
        return name;
    }

    /// Resolve a relative file name: the current file's folder, then the folders of the files that
    /// included it (innermost first), then the <path> folders in order.
    std::string resolvePath(const std::string& file, const SourceLocation& at) const {
        if (file.empty()) failAt(at, "empty file name");
        std::error_code ec;
        const fs::path p(file);
        std::vector<fs::path> candidates;
        if (p.is_absolute()) {
            candidates.push_back(p);
        } else {
            for (auto it = files_.rbegin(); it != files_.rend(); ++it) candidates.push_back(it->dir / p);
            for (const fs::path& d : searchPaths_) candidates.push_back(d / p);
        }
        std::string searched, folder;
        for (const fs::path& c : candidates) {
            if (fs::exists(c, ec) && !fs::is_directory(c, ec)) return fs::absolute(c, ec).lexically_normal().string();
            if (folder.empty() && fs::is_directory(c, ec)) folder = c.string();
            searched += (searched.empty() ? "" : ", ") + c.parent_path().string();
        }
        if (!folder.empty()) failAt(at, "'", file, "' is a directory, not a file (", folder, ")");
        failAt(at, "file '", file, "' not found (searched: ", searched, ")");
    }

    // ---------------------------------------------------------------- scene level
    void sceneChild(const pugi::xml_node& n) {
        const std::string tag = n.name();
        if (tag == "default") {
            checkAttributes(n, {"name", "value"});
            const std::string name = requiredAttr(n, "name");
            if (name.empty()) failAt(loc(n), "<default> with an empty name");
            const std::string value = requiredAttr(n, "value");
            params_.emplace(name, value);  // -D overrides and earlier defaults win
            declared_.insert(name);
        } else if (tag == "include") {
            checkAttributes(n, {"filename"});
            const SourceLocation at = loc(n);
            includeFile(resolvePath(requiredAttr(n, "filename"), at), at);
        } else if (tag == "path") {
            checkAttributes(n, {"value"});
            fs::path p(requiredAttr(n, "value"));
            if (p.is_relative()) p = files_.back().dir / p;
            searchPaths_.push_back(p);
        } else if (kObjectTags.count(tag)) {
            PropertiesPtr obj = parseObject(n, 0);
            scene_.objects.push_back(obj);
        } else if (kValueTags.count(tag) || tag == "ref") {
            failAt(loc(n), "<", tag, "> must be inside an object (bsdf, shape, emitter, ...)");
        } else {
            failAt(loc(n), "unknown element <", tag, ">");
        }
    }

    // ---------------------------------------------------------------- objects
    PropertiesPtr parseObject(const pugi::xml_node& n, int depth) {
        if (depth > kMaxNesting) failAt(loc(n), "objects nested too deeply (limit ", kMaxNesting, ")");
        checkAttributes(n, {"type", "id", "name"});
        auto props = std::make_shared<Properties>(n.name(), requiredAttr(n, "type"), loc(n));
        props->setFormatVersion(files_.back().major);
        props->setObjectCache(scene_.cache.get());
        std::string id;
        if (n.attribute("id")) {
            id = attr(n, "id");
            if (id.empty()) failAt(loc(n), "empty id");
            props->setId(id);
        }
        for (pugi::xml_node c = n.first_child(); c; c = c.next_sibling()) {
            if (c.type() != pugi::node_element) continue;
            const std::string tag = c.name();
            if (tag == "spectrum" && c.attribute("type")) {  // a spectrum plugin (Mitsuba 3), given by name
                if (!c.attribute("name")) failAt(loc(c), "<spectrum type=\"", attr(c, "type"), "\"> needs a name");
                props->set(paramName(c), parseObject(c, depth + 1), loc(c));
            } else if (kValueTags.count(tag)) {
                parseValue(c, *props);
            } else if (kObjectTags.count(tag)) {
                PropertiesPtr child = parseObject(c, depth + 1);
                if (c.attribute("name")) props->set(paramName(c), child, loc(c));
                else props->addChild(child);
                edges_[props.get()].push_back(child.get());
            } else if (tag == "ref") {
                // Resolved after the whole file is read: Mitsuba allows references to later ids.
                checkAttributes(c, {"id", "name"});
                PendingRef r{props, c.attribute("name") ? paramName(c) : std::string(), requiredAttr(c, "id"), loc(c)};
                pending_.push_back(std::move(r));
            } else if (tag == "default" || tag == "include" || tag == "path") {
                failAt(loc(c), "<", tag, "> is only allowed directly inside <scene>");
            } else {
                failAt(loc(c), "unknown element <", tag, "> inside <", n.name(), ">");
            }
        }
        if (!id.empty()) {
            const auto [it, inserted] = ids_.emplace(id, props);
            if (!inserted) failAt(loc(n), "duplicate id '", id, "' (first defined at ", it->second->location().str(), ")");
        }
        return props;
    }

    // ---------------------------------------------------------------- values
    vec3 xyzValue(const pugi::xml_node& n, float def) const {
        if (n.attribute("value")) {
            if (n.attribute("x") || n.attribute("y") || n.attribute("z"))
                failAt(loc(n), "<", n.name(), ">: give either value or x/y/z, not both");
            const std::vector<float> v = parseFloatList(attr(n, "value"), loc(n));
            if (v.size() == 1) return vec3(v[0]);
            if (v.size() != 3) failAt(loc(n), "<", n.name(), ">: expected 3 values, got ", v.size());
            return vec3(v[0], v[1], v[2]);
        }
        vec3 r(def);
        const char* names[3] = {"x", "y", "z"};
        for (int i = 0; i < 3; ++i)
            if (n.attribute(names[i])) r[i] = parseFloatValue(attr(n, names[i]), loc(n));
        return r;
    }

    vec3 vec3Attr(const pugi::xml_node& n, const char* name) const {
        const std::vector<float> v = parseFloatList(requiredAttr(n, name), loc(n));
        if (v.size() != 3) failAt(loc(n), "<", n.name(), "> attribute '", name, "' needs 3 values, got ", v.size());
        return vec3(v[0], v[1], v[2]);
    }

    void parseValue(const pugi::xml_node& n, Properties& props) {
        const std::string tag = n.name();
        const SourceLocation at = loc(n);
        if (tag == "transform") {
            checkAttributes(n, {"name"});
            props.set(paramName(n), parseTransform(n), at);
            return;
        }
        if (tag == "float") {
            checkAttributes(n, {"name", "value"});
            props.set(paramName(n), parseFloatValue(requiredAttr(n, "value"), at), at);
        } else if (tag == "integer") {
            checkAttributes(n, {"name", "value"});
            props.set(paramName(n), parseIntValue(requiredAttr(n, "value"), at), at);
        } else if (tag == "boolean") {
            checkAttributes(n, {"name", "value"});
            props.set(paramName(n), parseBoolValue(requiredAttr(n, "value"), at), at);
        } else if (tag == "string") {
            checkAttributes(n, {"name", "value"});
            const std::string name = paramName(n);
            std::string value = requiredAttr(n, "value");
            if (name == "filename") value = resolvePath(value, at);
            props.set(name, value, at);
        } else if (tag == "point" || tag == "vector") {
            checkAttributes(n, {"name", "value", "x", "y", "z"});
            const vec3 v = xyzValue(n, 0.0f);
            if (tag == "point") props.set(paramName(n), PointValue{v}, at);
            else props.set(paramName(n), VectorValue{v}, at);
        } else if (tag == "rgb" || tag == "srgb" || tag == "color") {
            checkAttributes(n, {"name", "value", "intent"});  // 0.6 'intent' is accepted and ignored
            props.set(paramName(n), RGBValue{parseColorValue(requiredAttr(n, "value"), tag == "srgb", at)}, at);
        } else if (tag == "spectrum") {
            checkAttributes(n, {"name", "value", "filename", "intent"});
            SpectrumValue sv;
            if (n.attribute("filename")) {
                if (n.attribute("value")) failAt(at, "<spectrum>: give either value or filename, not both");
                sv.type = SpectrumValue::Type::File;
                sv.path = resolvePath(attr(n, "filename"), at);
            } else {
                sv = parseSpectrumValue(requiredAttr(n, "value"), at);
            }
            props.set(paramName(n), sv, at);
        } else if (tag == "blackbody") {
            checkAttributes(n, {"name", "temperature", "scale"});
            SpectrumValue sv;
            sv.type = SpectrumValue::Type::Blackbody;
            std::string t = requiredAttr(n, "temperature");
            if (!t.empty() && (t.back() == 'K' || t.back() == 'k')) t.pop_back();  // 0.6 allowed "6500K"
            sv.temperature = parseFloatValue(t, at);
            if (!(sv.temperature > 0)) failAt(at, "blackbody temperature must be positive");
            if (n.attribute("scale")) sv.scale = parseFloatValue(attr(n, "scale"), at);
            props.set(paramName(n), sv, at);
        }
    }

    /// Transform operations applied in order; each pre-multiplies the matrix so far (Mitsuba).
    mat4 parseTransform(const pugi::xml_node& t) const {
        mat4 m(1.0f);
        for (pugi::xml_node n = t.first_child(); n; n = n.next_sibling()) {
            if (n.type() != pugi::node_element) continue;
            const std::string op = n.name();
            const SourceLocation at = loc(n);
            mat4 step(1.0f);
            if (op == "translate") {
                checkAttributes(n, {"value", "x", "y", "z"});
                step = glm::translate(mat4(1.0f), xyzValue(n, 0.0f));
            } else if (op == "scale") {
                checkAttributes(n, {"value", "x", "y", "z"});
                step = glm::scale(mat4(1.0f), xyzValue(n, 1.0f));
            } else if (op == "rotate") {
                checkAttributes(n, {"value", "x", "y", "z", "angle"});
                step = rotationMatrix(xyzValue(n, 0.0f), parseFloatValue(requiredAttr(n, "angle"), at), at);
            } else if (op == "matrix") {
                checkAttributes(n, {"value"});
                const std::vector<float> v = parseFloatList(requiredAttr(n, "value"), at);
                if (v.size() != 16 && v.size() != 9) failAt(at, "<matrix> needs 16 (or 9) values, got ", v.size());
                const int dim = v.size() == 16 ? 4 : 3;
                for (int r = 0; r < dim; ++r)
                    for (int c = 0; c < dim; ++c) step[c][r] = v[size_t(r * dim + c)];  // row-major text, column-major glm
            } else if (op == "lookat" || op == "lookAt") {
                checkAttributes(n, {"origin", "target", "up"});
                const vec3 up = n.attribute("up") ? vec3Attr(n, "up") : vec3(0, 1, 0);
                step = lookAtMatrix(vec3Attr(n, "origin"), vec3Attr(n, "target"), up, at);
            } else {
                failAt(at, "unknown transform operation <", op, "> (supported: translate, rotate, scale, matrix, lookat)");
            }
            m = step * m;
        }
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r)
                if (!std::isfinite(m[c][r])) failAt(loc(t), "the transform has non-finite entries");
        return m;
    }

    // ---------------------------------------------------------------- references
    struct PendingRef {
        PropertiesPtr owner;
        std::string name;  // empty: an unnamed child
        std::string id;
        SourceLocation loc;
    };

    void resolveRefs() {
        for (const PendingRef& r : pending_) {
            const auto it = ids_.find(r.id);
            if (it == ids_.end()) failAt(r.loc, "<ref>: unknown id '", r.id, "'");
            edges_[r.owner.get()].push_back(it->second.get());
            refLocations_.emplace(std::make_pair(r.owner.get(), it->second.get()), r.loc);
        }
        // A reference to an enclosing object would make object creation recurse forever (and the
        // shared pointers leak): check before linking anything.
        std::map<const Properties*, int> state;  // 1 = on the current path, 2 = done
        for (const auto& [node, out] : edges_) findCycle(node, state);
        for (const PendingRef& r : pending_) {
            const PropertiesPtr& target = ids_.at(r.id);
            if (!r.name.empty()) r.owner->set(r.name, target, r.loc);
            else r.owner->addChild(target);
        }
    }

    void findCycle(const Properties* node, std::map<const Properties*, int>& state) const {
        int& s = state[node];
        if (s == 2) return;
        s = 1;
        const auto it = edges_.find(node);
        if (it != edges_.end())
            for (const Properties* next : it->second) {
                if (state[next] == 1) {
                    const auto rl = refLocations_.find({node, next});
                    failAt(rl != refLocations_.end() ? rl->second : next->location(), "circular reference to '",
                           next->id(), "' (an object cannot contain itself)");
                }
                findCycle(next, state);
            }
        state[node] = 2;
    }

    std::vector<PendingRef> pending_;
    std::map<const Properties*, std::vector<const Properties*>> edges_;
    std::map<std::pair<const Properties*, const Properties*>, SourceLocation> refLocations_;
    std::map<std::string, std::string> params_;
    const std::map<std::string, std::string> defines_;  // -D overrides as given
    std::set<std::string> declared_;                    // names of <default> elements seen
    mutable std::set<std::string> used_;                // names substituted as $name
    std::map<std::string, PropertiesPtr> ids_;
    std::vector<fs::path> searchPaths_;
    std::vector<FileContext> files_;
    std::vector<std::string> openFiles_;
    ParsedScene scene_;
};

}  // namespace

ParsedScene parseSceneFile(const std::string& path, const std::map<std::string, std::string>& defines) {
    return XmlParser(defines).parseFile(path);
}

ParsedScene parseSceneString(const std::string& xml, const std::string& baseDir,
                             const std::map<std::string, std::string>& defines) {
    return XmlParser(defines).parseString(xml, baseDir);
}

}  // namespace iris
