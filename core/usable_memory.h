// How much memory this process may use: the least of the machine's physical memory, the memory
// limit of its control group (a Slurm job's or a container's, cgroup v2 memory.max or v1
// memory.limit_in_bytes, on the process's cgroup and every ancestor) and its address-space and data
// limits (`ulimit -v`, `ulimit -d`). The default memory budget is a fraction of it
// (core/memory_budget.h), so that a scene from the internet is refused with a message instead of
// exhausting a workstation or a cluster node (issue 38). The same bounds are what the JVM's
// container-aware default heap size reads (a fraction of the cgroup's limit when there is one).
#pragma once

#include <cstdint>
#include <optional>
#include <string>

namespace iris {

struct UsableMemory {
    uint64_t bytes = 0;
    std::string source;  // what set it, for messages: "physical memory", "cgroup memory.max", "ulimit -v", ...
};

/// The memory this process may use (see above); the physical memory if nothing else is smaller.
UsableMemory usableMemory();

/// The cgroup memory limit of the process whose /proc/self/cgroup text is `procSelfCgroup`, with
/// the cgroup file systems mounted at `cgroupRoot` (normally "/sys/fs/cgroup"): the least limit of
/// its cgroup and every ancestor, in v2 (memory.max) and v1 (memory/<path>/memory.limit_in_bytes)
/// layouts; none if no limit is set ("max", or v1's "no limit" near 2^63).
std::optional<uint64_t> cgroupMemoryLimit(const std::string& cgroupRoot, const std::string& procSelfCgroup);

}  // namespace iris
