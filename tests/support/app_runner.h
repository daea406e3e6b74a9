// Helpers for tests that run the built executables (render, compare, merge): paths, a shell
// runner that captures stdout and stderr, and temporary files.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

namespace iris::testing {

/// Folder of the built executables: IRIS_BUILD_DIR if set (CTest sets it), else the folder of
/// the running test binary (the apps are built beside it).
inline std::string buildDir() {
    if (const char* d = std::getenv("IRIS_BUILD_DIR")) return d;
    std::error_code ec;
    const auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
    return ec ? std::string(".") : exe.parent_path().string();
}

inline std::string appPath(const std::string& app) { return buildDir() + "/" + app; }

struct RunResult {
    int exitCode = -1;
    std::string stdoutText, stderrText;
};

/// The whole content of a file, byte for byte ("" if it cannot be read).
inline std::string fileBytes(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    std::stringstream ss;
    ss << f.rdbuf();
    return ss.str();
}

/// The whole content of a file ("" if it cannot be read), which is then removed.
inline std::string takeFile(const std::string& path) {
    std::string s = fileBytes(path);
    std::remove(path.c_str());
    return s;
}

/// `text` as one single-quoted word of the shell.
inline std::string shellQuote(const std::string& text) {
    std::string q = "'";
    for (char c : text) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
}

/// Seconds a command of runCommand may run before it is killed (issue 38: a hang must fail its test,
/// not stall CI): generous for the slowest app test (a few seconds on this 2-core machine, ten times
/// that under ASan), short against CTest's own per-test timeout (CMakeLists.txt).
inline constexpr int kCommandTimeoutSeconds = 300;

/// Run a shell command line, capturing its stdout and stderr. A command still running after
/// `timeoutSeconds` is killed with its children (coreutils' timeout: TERM, then KILL 5 s later) and
/// reports exit code 124.
inline RunResult runCommand(const std::string& cmd, int timeoutSeconds = kCommandTimeoutSeconds) {
    const std::string base = std::string(std::getenv("TMPDIR") ? std::getenv("TMPDIR") : "/tmp") + "/iris_test_" +
                             std::to_string(::getpid());
    const std::string outFile = base + "_stdout.txt", errFile = base + "_stderr.txt";
    const std::string guarded = "timeout -k 5 " + std::to_string(timeoutSeconds) + " /bin/sh -c " + shellQuote(cmd);
    const int status = std::system((guarded + " >" + outFile + " 2>" + errFile).c_str());
    RunResult r;
    r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.stdoutText = takeFile(outFile);
    r.stderrText = takeFile(errFile);
    return r;
}

/// A temporary file path private to this test process: <gtest TempDir>/<prefix>_<pid>_<name>.
inline std::string tempPath(const std::string& prefix, const std::string& name) {
    return (std::filesystem::path(::testing::TempDir()) / (prefix + "_" + std::to_string(::getpid()) + "_" + name)).string();
}

inline void writeTextFile(const std::string& path, const std::string& text) {
    std::ofstream f(path);
    f << text;
}

}  // namespace iris::testing
