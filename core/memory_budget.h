// The memory budget of a scene (issue 19 item 4): the large allocations a scene makes (meshes,
// textures, the film) are charged against a limit *before* they are made, from sizes a file's
// header or the film's resolution gives, so that a scene that would not fit stops with a clear
// message instead of being killed by the system (or thrashing it).
//
// The limit is set by `render --memory-limit SIZE` or the environment variable IRIS_MEMORY_LIMIT
// (read once, at the first charge); 0 means no limit. Unset, it is kDefaultLimitPercent of the
// memory the process may use (core/usable_memory.h: physical memory, or less under a cgroup limit or
// `ulimit -v`), so that no scene can exhaust a workstation or cluster node by default (issue 38).
// Charges made while a MemoryAccount
// lives on the thread are collected by it; the scene loader hands them to the scene it returns,
// so they are given back when that scene is destroyed (docs/testing.md, "Resource limits"). A
// charge outside any account (an image read by `compare`) is checked against the limit, not held.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>

namespace iris {

/// The default limit as a share of usableMemory(): half, leaving the other half for what is not
/// charged (Embree's build temporaries, per-thread arenas, libraries, the operating system's cache).
inline constexpr uint64_t kDefaultLimitPercent = 50;

/// The limit in bytes (0: none).
uint64_t memoryLimit();
void setMemoryLimit(uint64_t bytes);
/// kDefaultLimitPercent of usableMemory(), the limit when neither the option nor the variable is set.
uint64_t defaultMemoryLimit();
/// Bytes charged and not yet given back, in this process.
uint64_t memoryCharged();

/// "4G", "512M", "1.5GiB", "800KB", "1000000" → bytes. Units are binary (K = 1024, as `ulimit`
/// and Slurm's --mem count); "B" and "iB" are accepted after the unit; "0" means no limit.
/// Throws iris::Error naming the text on anything else.
uint64_t parseByteSize(std::string_view text);
/// 1536 → "1.5 KiB" (for messages).
std::string formatBytes(uint64_t bytes);

/// Charge `bytes` for `what` (a phrase naming the file and the object: "mesh.ply: 10^9 vertices").
/// Throws iris::Error "what needs X, over the memory limit of Y (Z already in use; set by
/// --memory-limit or IRIS_MEMORY_LIMIT)" if the total would exceed the limit; nothing is charged then.
/// Without a MemoryAccount on this thread the bytes are only checked against what is in use, not held.
void chargeMemory(uint64_t bytes, std::string_view what);

/// Check a transient allocation (a file read whole, then parsed and freed) against the limit and
/// what is in use, without holding it. Throws as chargeMemory does.
void checkMemory(uint64_t bytes, std::string_view what);

/// Bytes charged and held; given back to the budget when destroyed.
class MemoryReservation {
public:
    explicit MemoryReservation(uint64_t bytes = 0) : bytes_(bytes) {}
    ~MemoryReservation();
    MemoryReservation(const MemoryReservation&) = delete;
    MemoryReservation& operator=(const MemoryReservation&) = delete;
    uint64_t bytes() const { return bytes_; }

private:
    uint64_t bytes_;
};

/// Collects the charges made on this thread while it lives (accounts nest: the innermost one
/// collects). take() hands them over as one reservation; charges not taken are given back when
/// the account ends (a load that failed holds nothing).
class MemoryAccount {
public:
    MemoryAccount();
    ~MemoryAccount();
    MemoryAccount(const MemoryAccount&) = delete;
    MemoryAccount& operator=(const MemoryAccount&) = delete;
    std::shared_ptr<const MemoryReservation> take();

private:
    friend void chargeMemory(uint64_t, std::string_view);
    MemoryAccount* outer_;
    uint64_t bytes_ = 0;
};

}  // namespace iris
