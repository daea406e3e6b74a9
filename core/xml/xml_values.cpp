#include "core/xml/xml_values.h"

#include <cctype>
#include <charconv>

#include <glm/gtc/matrix_transform.hpp>

#include "core/srgb_transfer.h"

namespace iris {

namespace {
std::string trim(const std::string& s) {
    size_t b = 0, e = s.size();
    while (b < e && std::isspace(static_cast<unsigned char>(s[b]))) ++b;
    while (e > b && std::isspace(static_cast<unsigned char>(s[e - 1]))) --e;
    return s.substr(b, e - b);
}

std::vector<std::string> splitList(const std::string& s) {
    std::vector<std::string> out;
    std::string cur;
    for (char c : s) {
        if (c == ',' || std::isspace(static_cast<unsigned char>(c))) {
            if (!cur.empty()) out.push_back(cur);
            cur.clear();
        } else {
            cur += c;
        }
    }
    if (!cur.empty()) out.push_back(cur);
    return out;
}
}  // namespace

float parseFloatValue(const std::string& str, const SourceLocation& loc) {
    const std::string s = trim(str);
    const char* b = s.data();
    const char* e = b + s.size();
    if (b < e && *b == '+') ++b;
    float v = 0.0f;
    const auto [p, ec] = std::from_chars(b, e, v);
    if (ec != std::errc() || p != e || b == e) failAt(loc, "'", str, "' is not a valid number");
    if (!std::isfinite(v)) failAt(loc, "'", str, "' is not a finite number");
    return v;
}

int64_t parseIntValue(const std::string& str, const SourceLocation& loc) {
    const std::string s = trim(str);
    const char* b = s.data();
    const char* e = b + s.size();
    if (b < e && *b == '+') ++b;
    int64_t v = 0;
    const auto [p, ec] = std::from_chars(b, e, v);
    if (ec != std::errc() || p != e || b == e) failAt(loc, "'", str, "' is not a valid integer");
    return v;
}

bool parseBoolValue(const std::string& str, const SourceLocation& loc) {
    std::string s = trim(str);
    for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
    if (s == "true" || s == "1") return true;
    if (s == "false" || s == "0") return false;
    failAt(loc, "'", str, "' is not a boolean (true or false)");
}

std::vector<float> parseFloatList(const std::string& s, const SourceLocation& loc) {
    std::vector<float> out;
    for (const std::string& t : splitList(s)) out.push_back(parseFloatValue(t, loc));
    return out;
}

vec3 parseColorValue(const std::string& str, bool srgb, const SourceLocation& loc) {
    const std::string s = trim(str);
    vec3 c;
    if (srgb && !s.empty() && s[0] == '#') {
        if (s.size() != 7) failAt(loc, "'", str, "' is not a #rrggbb colour");
        for (int i = 0; i < 3; ++i) {
            unsigned v = 0;
            const auto [p, ec] = std::from_chars(s.data() + 1 + 2 * i, s.data() + 3 + 2 * i, v, 16);
            if (ec != std::errc() || p != s.data() + 3 + 2 * i) failAt(loc, "'", str, "' is not a #rrggbb colour");
            c[i] = float(v) / 255.0f;
        }
    } else {
        const std::vector<float> v = parseFloatList(s, loc);
        if (v.size() == 1) c = vec3(v[0]);
        else if (v.size() == 3) c = vec3(v[0], v[1], v[2]);
        else failAt(loc, "a colour needs 1 or 3 values, got ", v.size(), " in '", str, "'");
    }
    if (srgb)
        for (int i = 0; i < 3; ++i) c[i] = srgbToLinear(c[i]);
    return c;
}

SpectrumValue parseSpectrumValue(const std::string& str, const SourceLocation& loc) {
    SpectrumValue sv;
    const std::vector<std::string> items = splitList(str);
    if (items.empty()) failAt(loc, "empty spectrum value");
    if (items.size() == 1 && items[0].find(':') == std::string::npos) {
        sv.type = SpectrumValue::Type::Constant;
        sv.constant = parseFloatValue(items[0], loc);
        return sv;
    }
    sv.type = SpectrumValue::Type::Pairs;
    for (const std::string& it : items) {
        const size_t colon = it.find(':');
        if (colon == std::string::npos)
            failAt(loc, "spectrum values must be a single number or 'wavelength:value' pairs, got '", it, "'");
        const float lambda = parseFloatValue(it.substr(0, colon), loc);
        const float value = parseFloatValue(it.substr(colon + 1), loc);
        if (!sv.lambdas.empty() && lambda <= sv.lambdas.back())
            failAt(loc, "spectrum wavelengths must increase (", lambda, " after ", sv.lambdas.back(), ")");
        sv.lambdas.push_back(lambda);
        sv.values.push_back(value);
    }
    return sv;
}

std::string camelToSnake(const std::string& name) {
    std::string out;
    for (size_t i = 0; i < name.size(); ++i) {
        const unsigned char c = static_cast<unsigned char>(name[i]);
        if (std::isupper(c) && i > 0 && (std::islower(static_cast<unsigned char>(name[i - 1])) ||
                                         std::isdigit(static_cast<unsigned char>(name[i - 1]))))
            out += '_';
        out += char(std::tolower(c));
    }
    return out;
}

}  // namespace iris
