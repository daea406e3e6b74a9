#include "core/properties.h"


namespace iris {

namespace {
const char* typeName(const PropertyValue& v) {
    switch (v.index()) {
        case 0: return "boolean";
        case 1: return "integer";
        case 2: return "float";
        case 3: return "string";
        case 4: return "point";
        case 5: return "vector";
        case 6: return "rgb";
        case 7: return "spectrum";
        case 8: return "transform";
        default: return "object";
    }
}
}  // namespace

SourceLocation Properties::locationOf(const std::string& name) const {
    const auto it = values_.find(name);
    return it != values_.end() ? it->second.loc : loc_;
}

void Properties::set(const std::string& name, PropertyValue value, const SourceLocation& loc) {
    if (values_.count(name)) failAt(loc, "parameter '", name, "' is specified twice (first at ", values_[name].loc.str(), ")");
    values_[name] = Entry{std::move(value), loc};
}

const PropertyValue* Properties::peek(const std::string& name) const {
    const auto it = values_.find(name);
    return it == values_.end() ? nullptr : &it->second.value;
}

void Properties::replace(const std::string& name, PropertyValue value) {
    const auto it = values_.find(name);
    if (it == values_.end()) fail("Properties::replace: no parameter '", name, "'");
    it->second.value = std::move(value);
}

void Properties::rename(const std::string& from, const std::string& to) {
    const auto it = values_.find(from);
    if (it == values_.end()) fail("Properties::rename: no parameter '", from, "'");
    Entry e = std::move(it->second);
    values_.erase(it);
    if (const auto other = values_.find(to); other != values_.end()) {
        const bool fromFirst = e.loc.line < other->second.loc.line;
        const SourceLocation& first = fromFirst ? e.loc : other->second.loc;
        const SourceLocation& second = fromFirst ? other->second.loc : e.loc;
        failAt(second, "parameter '", to, "' is specified twice (first at ", first.str(), ")");
    }
    values_.emplace(to, std::move(e));
}

std::vector<std::string> Properties::names() const {
    std::vector<std::string> n;
    for (const auto& [k, v] : values_) n.push_back(k);
    return n;
}

bool Properties::present(const std::string& name) const {
    asked_.insert(name);
    return values_.count(name) > 0;
}

const Properties::Entry* Properties::find(const std::string& name) const {
    asked_.insert(name);
    const auto it = values_.find(name);
    if (it == values_.end()) return nullptr;
    queried_.insert(name);
    return &it->second;
}

const PropertiesPtr* Properties::peekObject(const std::string& name) const {
    const auto it = values_.find(name);
    return it == values_.end() ? nullptr : std::get_if<PropertiesPtr>(&it->second.value);
}

const Properties::Entry& Properties::require(const std::string& name) const {
    const Entry* e = find(name);
    if (!e) failAt(loc_, tag_, " '", type_, "': missing required parameter '", name, "'");
    return *e;
}

void Properties::typeError(const std::string& name, const char* expected) const {
    const Entry& e = values_.at(name);
    failAt(e.loc, "parameter '", name, "' of ", tag_, " '", type_, "' must be a ", expected, ", not a ",
           typeName(e.value));
}

bool Properties::getBool(const std::string& name) const {
    const Entry& e = require(name);
    if (const bool* b = std::get_if<bool>(&e.value)) return *b;
    typeError(name, "boolean");
}
bool Properties::getBool(const std::string& name, bool def) const { return present(name) ? getBool(name) : def; }

int Properties::getInt(const std::string& name) const {
    const Entry& e = require(name);
    if (const int64_t* i = std::get_if<int64_t>(&e.value)) {
        if (*i < INT32_MIN || *i > INT32_MAX) failAt(e.loc, "integer parameter '", name, "' is out of range");
        return int(*i);
    }
    typeError(name, "integer");
}
int Properties::getInt(const std::string& name, int def) const { return present(name) ? getInt(name) : def; }

float Properties::getFloat(const std::string& name) const {
    const Entry& e = require(name);
    if (const float* f = std::get_if<float>(&e.value)) return *f;
    if (const int64_t* i = std::get_if<int64_t>(&e.value)) return float(*i);
    typeError(name, "float");
}
float Properties::getFloat(const std::string& name, float def) const { return present(name) ? getFloat(name) : def; }

std::string Properties::getString(const std::string& name) const {
    const Entry& e = require(name);
    if (const std::string* s = std::get_if<std::string>(&e.value)) return *s;
    typeError(name, "string");
}
std::string Properties::getString(const std::string& name, const std::string& def) const {
    return present(name) ? getString(name) : def;
}

vec3 Properties::getPoint(const std::string& name) const {
    const Entry& e = require(name);
    if (const PointValue* p = std::get_if<PointValue>(&e.value)) return p->v;
    if (const VectorValue* p = std::get_if<VectorValue>(&e.value)) return p->v;
    typeError(name, "point");
}
vec3 Properties::getPoint(const std::string& name, const vec3& def) const { return present(name) ? getPoint(name) : def; }

vec3 Properties::getVector(const std::string& name) const {
    const Entry& e = require(name);
    if (const VectorValue* p = std::get_if<VectorValue>(&e.value)) return p->v;
    if (const PointValue* p = std::get_if<PointValue>(&e.value)) return p->v;
    typeError(name, "vector");
}
vec3 Properties::getVector(const std::string& name, const vec3& def) const { return present(name) ? getVector(name) : def; }

vec3 Properties::getRGB(const std::string& name, const vec3& def) const {
    const Entry* e = find(name);
    if (!e) return def;
    if (const RGBValue* c = std::get_if<RGBValue>(&e->value)) return c->rgb;
    if (const float* f = std::get_if<float>(&e->value)) return vec3(*f);
    if (const VectorValue* v = std::get_if<VectorValue>(&e->value)) return v->v;
    if (const PointValue* v = std::get_if<PointValue>(&e->value)) return v->v;
    typeError(name, "rgb");
}

mat4 Properties::getTransform(const std::string& name, const mat4& def) const {
    const Entry* e = find(name);
    if (!e) return def;
    if (const mat4* m = std::get_if<mat4>(&e->value)) return *m;
    typeError(name, "transform");
}

PropertiesPtr Properties::getObject(const std::string& name, bool required) const {
    const Entry* e = required ? &require(name) : find(name);
    if (!e) return nullptr;
    if (const PropertiesPtr* p = std::get_if<PropertiesPtr>(&e->value)) return *p;
    typeError(name, "nested object");
}

void Properties::checkUnqueried() const {
    std::string known, all;
    for (const auto& q : asked_) known += (known.empty() ? "" : ", ") + q;
    for (const auto& [name, entry] : values_) {
        if (queried_.count(name)) continue;
        const Error e(entry.loc, strCat("unknown parameter '", name, "' of ", tag_, " '", type_, "'",
                                        known.empty() ? std::string() : " (known parameters: " + known + ")"));
        all += (all.empty() ? "" : "\n") + std::string(e.what());
    }
    if (!all.empty()) throw Error(all);  // every unknown parameter, one "file:line: ..." line each
}

}  // namespace iris
