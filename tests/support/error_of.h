// The message of the iris::Error a callable throws, for tests that check error messages.
#pragma once

#include <string>

#include "core/error.h"

namespace iris::test {

/// The message of the iris::Error that f throws ("" when it throws none).
template <typename F>
std::string errorOf(F&& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.what();
    }
    return {};
}

/// The error of loading a scene of format `version` whose body (the elements inside <scene>, from
/// line 2 on) is `body` ("" when it loads).
std::string sceneError(const std::string& body, const std::string& version = "3.0.0");

/// Whether `part` occurs in the message `s`.
inline bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

}  // namespace iris::test
