#include "core/usable_memory.h"

#include <sys/resource.h>
#include <unistd.h>

#include <charconv>
#include <fstream>
#include <sstream>

namespace iris {

namespace {

/// The number in a cgroup limit file ("max\n" and v1's "no limit", 2^63 rounded to pages: none).
std::optional<uint64_t> readLimitFile(const std::string& path) {
    std::ifstream f(path);
    std::string word;
    if (!(f >> word) || word == "max") return std::nullopt;
    uint64_t v = 0;
    const auto [p, ec] = std::from_chars(word.data(), word.data() + word.size(), v);
    if (ec != std::errc() || p != word.data() + word.size() || v >= (uint64_t(1) << 62)) return std::nullopt;
    return v;
}

/// The least limit in `file` of the cgroup at `dir` and each of its ancestors up to `root`.
std::optional<uint64_t> leastLimitUpwards(const std::string& root, std::string dir, const std::string& file) {
    std::optional<uint64_t> least;
    for (;;) {
        if (const auto v = readLimitFile(root + dir + "/" + file); v && (!least || *v < *least)) least = v;
        if (dir.empty() || dir == "/") return least;
        dir = dir.substr(0, dir.find_last_of('/'));
    }
}

void keepSmaller(UsableMemory& m, uint64_t bytes, const char* source) {
    if (bytes > 0 && bytes < m.bytes) m = UsableMemory{bytes, source};
}

std::string fileText(const char* path) {
    std::ifstream f(path);
    std::stringstream ss;
    ss << f.rdbuf();
    return ss.str();
}

}  // namespace

std::optional<uint64_t> cgroupMemoryLimit(const std::string& cgroupRoot, const std::string& procSelfCgroup) {
    std::optional<uint64_t> least;
    std::istringstream lines(procSelfCgroup);
    std::string line;
    while (std::getline(lines, line)) {  // "hierarchy-ID:controller-list:cgroup-path" (cgroups(7))
        const size_t a = line.find(':'), b = a == std::string::npos ? a : line.find(':', a + 1);
        if (b == std::string::npos) continue;
        const std::string controllers = line.substr(a + 1, b - a - 1), path = line.substr(b + 1);
        std::optional<uint64_t> v;
        if (controllers.empty()) v = leastLimitUpwards(cgroupRoot, path, "memory.max");  // v2
        else if (("," + controllers + ",").find(",memory,") != std::string::npos)
            v = leastLimitUpwards(cgroupRoot + "/memory", path, "memory.limit_in_bytes");  // v1
        if (v && (!least || *v < *least)) least = v;
    }
    return least;
}

UsableMemory usableMemory() {
    UsableMemory m{uint64_t(::sysconf(_SC_PHYS_PAGES)) * uint64_t(::sysconf(_SC_PAGESIZE)), "physical memory"};
    if (const auto c = cgroupMemoryLimit("/sys/fs/cgroup", fileText("/proc/self/cgroup"))) keepSmaller(m, *c, "its cgroup's memory limit");
    struct rlimit r {};
    if (::getrlimit(RLIMIT_AS, &r) == 0 && r.rlim_cur != RLIM_INFINITY) keepSmaller(m, uint64_t(r.rlim_cur), "ulimit -v");
    if (::getrlimit(RLIMIT_DATA, &r) == 0 && r.rlim_cur != RLIM_INFINITY) keepSmaller(m, uint64_t(r.rlim_cur), "ulimit -d");
    return m;
}

}  // namespace iris
