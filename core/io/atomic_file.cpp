// Atomic file output (core/io/atomic_file.h): temporary file, fsync, rename, fsync of the folder.
#include "core/io/atomic_file.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include "core/error.h"

namespace iris {

namespace {

/// A non-negative byte count from the environment variable `name` (-1 if unset or malformed).
long long envBytes(const char* name) {
    const char* v = std::getenv(name);
    if (!v || !*v) return -1;
    char* end = nullptr;
    const long long n = std::strtoll(v, &end, 10);
    return (*end == '\0' && n >= 0) ? n : -1;
}

/// IRIS_FAULT_DISK_FULL_AFTER: bytes a write may put in one file before failing (-1 = no limit).
long long injectedDiskSpace() { return envBytes("IRIS_FAULT_DISK_FULL_AFTER"); }

/// IRIS_FAULT_KILL_WRITING: bytes a write puts in its temporary before the process kills itself
/// with SIGKILL (-1 = never), as a kill -9 in the middle of writing a checkpoint would.
long long injectedKillPoint() { return envBytes("IRIS_FAULT_KILL_WRITING"); }

[[noreturn]] void failErrno(const std::string& path, const char* what, int err) {
    fail(path, ": ", what, ": ", std::strerror(err));
}

/// Removes the temporary file unless released (after the rename).
class TempFile {
public:
    explicit TempFile(std::string path) : path_(std::move(path)) {}
    ~TempFile() {
        if (!path_.empty()) ::unlink(path_.c_str());
    }
    TempFile(const TempFile&) = delete;
    TempFile& operator=(const TempFile&) = delete;
    const std::string& path() const { return path_; }
    void release() { path_.clear(); }

private:
    std::string path_;
};

/// Write all of `bytes` to `fd` (EINTR and short writes retried).
void writeAll(int fd, std::string_view bytes, const std::string& path) {
    const long long space = injectedDiskSpace(), killAt = injectedKillPoint();
    size_t done = 0;
    while (done < bytes.size()) {
        if (space >= 0 && done >= size_t(space)) failErrno(path, "write failed", ENOSPC);
        if (killAt >= 0 && done >= size_t(killAt)) ::raise(SIGKILL);
        size_t chunk = bytes.size() - done;
        if (space >= 0) chunk = std::min(chunk, size_t(space) - done);
        if (killAt >= 0) chunk = std::min(chunk, size_t(killAt) - done);
        const ssize_t n = ::write(fd, bytes.data() + done, chunk);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) failErrno(path, "write failed", errno);
        done += size_t(n);
    }
}

void fsyncPath(const std::string& p, int flags, const std::string& reportAs) {
    const int fd = ::open(p.c_str(), flags | O_CLOEXEC);
    if (fd < 0) failErrno(reportAs, "cannot open for fsync", errno);
    const int rc = ::fsync(fd);
    const int err = errno;
    ::close(fd);
    // Some file systems cannot fsync a folder (EINVAL): the rename itself is still atomic.
    if (rc != 0 && !(flags & O_DIRECTORY && err == EINVAL)) failErrno(reportAs, "fsync failed", err);
}

std::string folderOf(const std::string& path) {
    const std::filesystem::path parent = std::filesystem::path(path).parent_path();
    return parent.empty() ? std::string(".") : parent.string();
}

/// IRIS_FAULT_SIGNAL_BEFORE_RENAME=INT|TERM|KILL: raise that signal once the temporary is complete,
/// just before it is renamed over the path (the last moment a signal can meet a write).
void raiseInjectedSignalBeforeRename() {
    const char* v = std::getenv("IRIS_FAULT_SIGNAL_BEFORE_RENAME");
    if (!v || !*v) return;
    const std::string name = v;
    ::raise(name == "KILL" ? SIGKILL : name == "TERM" ? SIGTERM : SIGINT);
}

/// IRIS_FAULT_UNWRITABLE=PATH: an atomic write of exactly PATH fails, as on a file system remounted
/// read-only after the output was checked (the fallback tests of core/io/output_file.h).
void failIfInjectedUnwritable(const std::string& path) {
    const char* v = std::getenv("IRIS_FAULT_UNWRITABLE");
    if (v && path == v) failErrno(path, "cannot create file", EROFS);
}

/// Make the finished temporary durable and move it over `path`.
void commit(TempFile& tmp, const std::string& path) {
    raiseInjectedSignalBeforeRename();
    const long long space = injectedDiskSpace();
    struct stat st{};
    if (space >= 0 && ::stat(tmp.path().c_str(), &st) == 0 && st.st_size > space) failErrno(path, "write failed", ENOSPC);
    fsyncPath(tmp.path(), O_RDONLY, path);
    if (std::rename(tmp.path().c_str(), path.c_str()) != 0) failErrno(path, "cannot move the written file into place", errno);
    tmp.release();
    fsyncPath(folderOf(path), O_RDONLY | O_DIRECTORY, path);
}

}  // namespace

std::string atomicTempPath(const std::string& path) {
    static std::atomic<unsigned long long> counter{0};
    return strCat(path, ".tmp-", ::getpid(), "-", counter++);
}

void writeFileAtomically(const std::string& path, std::string_view bytes) {
    failIfInjectedUnwritable(path);
    TempFile tmp(atomicTempPath(path));
    const int fd = ::open(tmp.path().c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
    if (fd < 0) {
        tmp.release();  // nothing was created
        failErrno(path, "cannot create file", errno);
    }
    try {
        writeAll(fd, bytes, path);
    } catch (...) {
        ::close(fd);
        throw;
    }
    if (::close(fd) != 0) failErrno(path, "write failed", errno);
    commit(tmp, path);
}

void writeFileAtomicallyWith(const std::string& path, const std::function<void(const std::string& tempPath)>& writeTemp) {
    failIfInjectedUnwritable(path);
    TempFile tmp(atomicTempPath(path));
    writeTemp(tmp.path());
    commit(tmp, path);
}

}  // namespace iris
