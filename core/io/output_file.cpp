#include "core/io/output_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include "core/error.h"
#include "core/io/atomic_file.h"

namespace iris {

namespace fs = std::filesystem;

namespace {

std::string folderOf(const std::string& path) {
    const fs::path parent = fs::path(path).parent_path();
    return parent.empty() ? std::string(".") : parent.string();
}

/// Create and remove a file in `folder` as the atomic writer will (errno of the failure, or 0).
int probeFolder(const std::string& folder) {
    const std::string probe = atomicTempPath((fs::path(folder) / ".iris-write-probe").string());
    const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
    if (fd < 0) return errno;
    ::close(fd);
    ::unlink(probe.c_str());
    return 0;
}

}  // namespace

void checkOutputPath(const std::string& path, std::string_view option) {
    if (path.empty()) fail(option, ": the output path is empty");
    struct stat st {};
    if (::stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode))
        fail(option, " ", path, ": ", S_ISDIR(st.st_mode) ? "is a directory; give a file name" : "exists and is not a regular file");
    const std::string folder = folderOf(path);
    if (::stat(folder.c_str(), &st) != 0) fail(option, " ", path, ": the folder ", folder, " does not exist");
    if (!S_ISDIR(st.st_mode)) fail(option, " ", path, ": ", folder, " is not a folder");
    if (const int err = probeFolder(folder))
        fail(option, " ", path, ": cannot create a file in the folder ", folder, ": ", std::strerror(err));
}

std::string temporaryFolder() {
    const char* tmp = std::getenv("TMPDIR");
    return tmp && *tmp ? tmp : "/tmp";
}

std::vector<std::string> fallbackPaths(const std::string& path) {
    const std::string name = strCat("iris-rescued-", ::getpid(), "-", fs::path(path).filename().string());
    std::vector<std::string> out;
    std::error_code ec, gone;
    const fs::path cwd = fs::current_path(ec);
    const bool sameFolder = fs::equivalent(cwd, folderOf(path), gone) && !gone;  // a removed folder is not the same
    if (!ec && !sameFolder) out.push_back((cwd / name).string());
    out.push_back((fs::path(temporaryFolder()) / name).string());
    return out;
}

void writeWithFallback(const std::string& path, const std::function<void(const std::string&)>& write) {
    try {
        write(path);
        return;
    } catch (const Error& first) {
        std::string tried;
        for (const std::string& p : fallbackPaths(path)) {
            try {
                write(p);
            } catch (const Error&) {
                tried += (tried.empty() ? "" : ", ") + p;
                continue;
            }
            fail(first.what(), "; written to ", p, " instead");
        }
        fail(first.what(), "; not written to a fallback either (", tried, ")");
    }
}

}  // namespace iris
