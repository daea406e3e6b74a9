// Shared pieces of the libFuzzer targets (tests/fuzz/fuzz_*.cpp, docs/testing.md "Fuzzing"): every
// target feeds one input to one of iris's readers of untrusted files and accepts exactly two
// outcomes, a result or an iris::Error. Anything else (another exception type, a crash, a
// sanitizer report, a huge allocation, a hang) is a finding: the target aborts so that libFuzzer
// saves the input.
#pragma once

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>

#include "core/error.h"

namespace iris::fuzz {

/// A private scratch folder for this process (readers that only take paths get their input as a
/// file in it), removed when the process exits normally; a crash keeps it with the input.
inline const std::filesystem::path& scratchDir() {
    struct Scratch {
        std::filesystem::path dir;
        ~Scratch() {
            std::error_code ec;
            std::filesystem::remove_all(dir, ec);
        }
    };
    static const Scratch scratch = [] {
        const char* t = std::getenv("TMPDIR");
        std::filesystem::path d = std::filesystem::path(t && *t ? t : "/tmp") / ("iris_fuzz_" + std::to_string(::getpid()));
        std::filesystem::create_directories(d);
        return Scratch{d};
    }();
    return scratch.dir;
}

/// Write the input to <scratch>/<name> (overwritten on every call) and return its path.
inline std::string writeInput(const uint8_t* data, size_t size, const std::string& name) {
    const std::string path = (scratchDir() / name).string();
    std::ofstream f(path, std::ios::binary | std::ios::trunc);
    f.write(reinterpret_cast<const char*>(data), std::streamsize(size));
    return path;
}

/// Run `read`; an iris::Error is the expected refusal of bad input, any other exception aborts.
/// IRIS_FUZZ_VERBOSE=1 prints each refusal (to check that seeds are accepted).
template <typename F>
void expectResultOrIrisError(F&& read) {
    try {
        read();
    } catch (const Error& e) {
        static const bool verbose = std::getenv("IRIS_FUZZ_VERBOSE") != nullptr;
        if (verbose) std::fprintf(stderr, "refused: %s\n", e.what());
    } catch (const std::exception& e) {
        std::fprintf(stderr, "fuzz: unexpected exception (not iris::Error): %s\n", e.what());
        std::abort();
    } catch (...) {
        std::fprintf(stderr, "fuzz: unexpected non-standard exception\n");
        std::abort();
    }
}

}  // namespace iris::fuzz
