#include "core/input_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "core/error.h"
#include "core/memory_budget.h"

namespace iris {

namespace {

const char* fileTypeName(mode_t mode) {
    if (S_ISDIR(mode)) return "a directory";
    if (S_ISCHR(mode)) return "a character device";
    if (S_ISBLK(mode)) return "a block device";
    if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
    if (S_ISSOCK(mode)) return "a socket";
    return "not a regular file";
}

[[noreturn]] void failToOpen(const std::string& path, std::string_view kind, int err) {
    if (err == ENOENT || err == ENOTDIR) fail(path, ": cannot open ", kind, ": file not found");
    fail(path, ": cannot open ", kind, ": ", std::strerror(err));
}

/// The file's size, once `st` is known to describe a regular file within the format's limit.
uint64_t checkedSize(const struct stat& st, const std::string& path, std::string_view kind, uint64_t maxBytes) {
    if (!S_ISREG(st.st_mode)) {
        if (S_ISDIR(st.st_mode)) fail(path, ": cannot open ", kind, ": it is a directory, not a regular file");
        fail(path, ": cannot open ", kind, ": it is ", fileTypeName(st.st_mode), ", not a regular file");
    }
    const uint64_t size = uint64_t(st.st_size);
    if (size > maxBytes)
        fail(path, ": ", kind, " of ", formatBytes(size), " exceeds the limit of ", formatBytes(maxBytes), " for a ", kind);
    return size;
}

/// A descriptor closed on every exit.
struct Descriptor {
    int fd = -1;
    ~Descriptor() {
        if (fd >= 0) ::close(fd);
    }
};

/// stat() first, so that a device or FIFO is never opened; then open without blocking (a FIFO put
/// in the file's place meanwhile returns at once) and check the open descriptor again.
uint64_t openChecked(const std::string& path, std::string_view kind, uint64_t maxBytes, Descriptor& d) {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0) failToOpen(path, kind, errno);
    checkedSize(st, path, kind, maxBytes);
    d.fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
    if (d.fd < 0) failToOpen(path, kind, errno);
    if (::fstat(d.fd, &st) != 0) failToOpen(path, kind, errno);
    return checkedSize(st, path, kind, maxBytes);
}

}  // namespace

uint64_t checkInputFile(const std::string& path, std::string_view kind, uint64_t maxBytes) {
    Descriptor d;
    return openChecked(path, kind, maxBytes, d);
}

std::string readInputFile(const std::string& path, std::string_view kind, uint64_t maxBytes) {
    Descriptor d;
    const uint64_t size = openChecked(path, kind, maxBytes, d);
    checkMemory(size, strCat(path, ": reading the ", kind));
    std::string data(size_t(size), '\0');
    size_t done = 0;
    while (done < data.size()) {
        const ssize_t n = ::read(d.fd, data.data() + done, data.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) fail(path, ": read error: ", std::strerror(errno));
        if (n == 0) fail(path, ": read error (", done, " of ", size, " bytes; the file shrank while it was read)");
        done += size_t(n);
    }
    return data;
}

}  // namespace iris
