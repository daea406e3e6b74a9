// Error reporting: every user-facing problem is an iris::Error whose message already names the
// file (and line) concerned; apps print it on one line and exit non-zero.
#pragma once

#include <sstream>
#include <stdexcept>
#include <string>

namespace iris {

/// Where something came from in an input file (line 0 = unknown / whole file).
struct SourceLocation {
    std::string file;
    int line = 0;

    std::string str() const {
        if (file.empty()) return {};
        return line > 0 ? file + ":" + std::to_string(line) : file;
    }
};

/// Concatenate anything streamable into a string: strCat("x = ", 3, "!").
template <typename... Args>
std::string strCat(const Args&... args) {
    std::ostringstream os;
    (os << ... << args);
    return os.str();
}

class Error : public std::runtime_error {
public:
    explicit Error(const std::string& msg) : std::runtime_error(msg) {}
    Error(const SourceLocation& loc, const std::string& msg)
        : std::runtime_error(loc.file.empty() ? msg : loc.str() + ": " + msg) {}
};

template <typename... Args>
[[noreturn]] void fail(const Args&... args) {
    throw Error(strCat(args...));
}

template <typename... Args>
[[noreturn]] void failAt(const SourceLocation& loc, const Args&... args) {
    throw Error(loc, strCat(args...));
}

/// Run f(); an iris::Error it throws (a file error naming its file, a bad enum value) is rethrown
/// with the scene location that asked for it in front: "scene.xml:12: <prefix><message>".
template <typename F>
decltype(auto) withLocation(const SourceLocation& loc, F&& f, const std::string& prefix = "") {
    try {
        return f();
    } catch (const Error& e) {
        failAt(loc, prefix, e.what());
    }
}

}  // namespace iris
