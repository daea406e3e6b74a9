// The memory the process may use (core/usable_memory.h) and the default memory budget made from it
// (issue 38): cgroup limits are read in both layouts, on the process's cgroup and its ancestors.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/memory_budget.h"
#include "core/usable_memory.h"
#include "tests/support/app_runner.h"

using namespace iris;
namespace fs = std::filesystem;

namespace {

/// A fake cgroup file system under a temporary folder: writes `text` to <root>/<file>.
struct FakeCgroups {
    std::string root = iris::testing::tempPath("usable_memory", "cgroup");
    FakeCgroups() { fs::remove_all(root); }
    ~FakeCgroups() { fs::remove_all(root); }
    void set(const std::string& file, const std::string& text) const {
        fs::create_directories(fs::path(root + file).parent_path());
        std::ofstream(root + file) << text;
    }
};

}  // namespace

TEST(UsableMemory, CgroupV2TakesTheLeastLimitOfTheCgroupAndItsAncestors) {
    const FakeCgroups cg;
    cg.set("/job/step/memory.max", "max\n");
    cg.set("/job/memory.max", "1073741824\n");
    cg.set("/memory.max", "4294967296\n");
    EXPECT_EQ(cgroupMemoryLimit(cg.root, "0::/job/step\n"), uint64_t(1) << 30);
    cg.set("/job/step/memory.max", "536870912\n");
    EXPECT_EQ(cgroupMemoryLimit(cg.root, "0::/job/step\n"), uint64_t(1) << 29);
}

TEST(UsableMemory, CgroupV1ReadsTheMemoryControllerAndItsNoLimitValue) {
    const FakeCgroups cg;
    cg.set("/memory/slurm/job_7/memory.limit_in_bytes", "9223372036854771712\n");  // v1's "no limit"
    const std::string self = "9:pids:/slurm/job_7\n4:memory:/slurm/job_7\n1:cpu,cpuacct:/\n";
    EXPECT_EQ(cgroupMemoryLimit(cg.root, self), std::nullopt);
    cg.set("/memory/slurm/memory.limit_in_bytes", "2147483648\n");
    EXPECT_EQ(cgroupMemoryLimit(cg.root, self), uint64_t(2) << 30);
    EXPECT_EQ(cgroupMemoryLimit(cg.root, "9:pids:/slurm/job_7\n"), std::nullopt);  // no memory controller
}

TEST(UsableMemory, TheDefaultBudgetIsHalfOfWhatTheProcessMayUse) {
    const UsableMemory m = usableMemory();
    EXPECT_GT(m.bytes, uint64_t(64) << 20) << m.source;
    EXPECT_EQ(defaultMemoryLimit(), m.bytes / 100 * 50);
}
